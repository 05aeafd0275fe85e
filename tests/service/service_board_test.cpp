// The extruder board restarting under a print, with the binaries as on a cell (mock-gt2560 and
// fibrecell-simcell as processes of their own): the print pauses with the board's fault, the
// cell stops showing the lost board's temperatures, and `resume` opens the link again, heats the
// hotends, selects the print's head and finishes the job, with no service restart.
#include "external_cell.hpp"
#include "service_fixture.hpp"

#include <gmock/gmock.h>

#include <algorithm>
#include <sstream>
#include <vector>

using namespace fibrecell;
using namespace fibrecell::test;
using ::testing::HasSubstr;

namespace {

constexpr double board_time_scale = 50;

// The commands of the board's --log (time, tab, command), in order.
std::vector<std::string> board_commands(const fs::path& log) {
    std::vector<std::string> out;
    std::istringstream in(read_file(log));
    std::string line;
    while (std::getline(in, line)) {
        const auto tab = line.find('\t');
        if (tab != std::string::npos) out.push_back(line.substr(tab + 1));
    }
    return out;
}

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// How many cut events the plan's program.json has.
int planned_cuts(const fs::path& program_json) {
    int cuts = 0;
    for (const auto& [sequence, e] : planned_events(program_json)) cuts += e.kind == "cut";
    return cuts;
}

}  // namespace

TEST_F(ServiceTest, ABoardThatRestartsMidPrintIsConnectedAgainByTheResume) {
    ExternalCell devices(dir_, board_time_scale, /*board_control=*/true);
    ASSERT_TRUE(devices.up());
    std::ofstream(dir_ / "cell.yaml") << devices.cell_yaml(read_file(write_config("", board_time_scale)));
    start_service(dir_ / "cell.yaml");
    auto c = client();
    const std::int64_t id = submit_bar(c, true);
    ASSERT_EQ(wait_for_state(c, id, "printing", 120s).value("state", ""), "printing") << service_->log();
    // Some way into the print, then the board resets (a brown-out, a DTR pulse).
    ASSERT_TRUE(eventually([&] {
        const json j = c.call("job.get", {{"job", id}});
        return j.contains("print") && j["print"].value("event", 0) >= 8;
    }, 120s));
    ASSERT_TRUE(devices.board_command("reset"));

    const json paused = wait_for_state(c, id, "paused", 60s);
    ASSERT_EQ(paused.value("state", ""), "paused") << paused.dump(2) << service_->log();
    EXPECT_THAT(paused.value("reason", ""), HasSubstr("extruder board"));
    const json board = c.call("cell.status")["board"];
    EXPECT_NE(board.value("state", ""), "active");
    EXPECT_FALSE(board.contains("pla_c")) << board.dump();  // not the lost board's last reading

    ASSERT_EQ(c.call("job.resume", {{"job", id}}).value("state", ""), "printing");
    const json done = wait_for_state(c, id, "completed", 180s);
    const std::string state = done.value("state", "");
    ASSERT_TRUE(state == "completed" || state == "completed_with_warnings")
        << done.dump(2) << "\n" << service_->log();
    EXPECT_EQ(done["result"]["events_done"], done["result"]["events"]);
    // result.json times every cut of the print, before the restart and after it.
    EXPECT_EQ(done["result"]["cut_error_mm"].value("count", 0),
              planned_cuts(state_dir() / "jobs" / std::to_string(id) / "plan" / "program.json"))
        << done["result"].dump();
    const json after = c.call("cell.status")["board"];
    EXPECT_EQ(after.value("state", ""), "active");
    EXPECT_TRUE(after.contains("pla_c")) << after.dump();

    // On the board after its restart: relative E, both hotends heated and waited for, and a head
    // selected, all before the first extrusion or feed.
    // The link's handshake (M110) opens each connection: the second one is the reconnect.
    const std::vector<std::string> all = board_commands(devices.board_log());
    std::vector<std::size_t> handshakes;
    for (std::size_t i = 0; i < all.size(); ++i)
        if (starts_with(all[i], "M110")) handshakes.push_back(i);
    ASSERT_GE(handshakes.size(), 2u);
    bool relative = false, selected = false;
    int waits = 0;
    for (std::size_t i = handshakes[1]; i < all.size(); ++i) {
        const std::string& cmd = all[i];
        if (starts_with(cmd, "G1") && cmd.find(" E") != std::string::npos) break;
        relative = relative || cmd == "M83";
        waits += starts_with(cmd, "M109");
        selected = selected || cmd == "T0" || cmd == "T1";
    }
    EXPECT_TRUE(relative);
    EXPECT_GE(waits, 2);
    EXPECT_TRUE(selected);
    EXPECT_TRUE(service_->terminate(20s));
}
