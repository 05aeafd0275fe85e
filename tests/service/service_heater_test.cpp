// The hotends follow the job (docs/service.md, "Heaters"): off when a print completes, is aborted,
// or is given up after a fault; kept hot for the cell's hold when it asks for one; off when the
// cell has had no job for its idle timeout, and when the service stops. Read from the mock
// board's own heater targets (mock-gt2560's `heaters`), not from what the service believes.
#include "external_cell.hpp"
#include "service_fixture.hpp"

#include <gmock/gmock.h>

using namespace fibrecell;
using namespace fibrecell::test;
using ::testing::HasSubstr;

namespace {

constexpr double heater_time_scale = 50;

class HeaterTest : public ServiceTest {
  protected:
    // The board keeps its heaters when the service opens its port again (its auto-reset off),
    // so that only the service's M104 S0 turns them off.
    void start_cell(const std::string& extra = "") {
        devices_.emplace(dir_, heater_time_scale, /*board_control=*/true,
                         std::vector<std::string>{"--no-reset-on-open"});
        ASSERT_TRUE(devices_->up());
        std::ofstream(dir_ / "cell.yaml")
            << devices_->cell_yaml(read_file(write_config(extra, heater_time_scale)));
        start_service(dir_ / "cell.yaml");
    }

    // Both of the board's targets at 0.
    bool board_heaters_off() {
        const auto t = devices_->board_heater_targets();
        return t && t->first == 0 && t->second == 0;
    }
    bool board_heating() {
        const auto t = devices_->board_heater_targets();
        return t && t->first > 0 && t->second > 0;
    }

    // Submitted and started (the last print's part taken off first: docs/queue.md); returns
    // once it has confirmed `event`.
    std::int64_t print_until(api::ApiClient& c, int event) {
        c.call("cell.clear");
        const std::int64_t id = submit_bar(c, true);
        EXPECT_EQ(wait_for_state(c, id, "printing", 120s).value("state", ""), "printing") << service_->log();
        EXPECT_TRUE(eventually([&] {
            const json j = c.call("job.get", {{"job", id}});
            return j.contains("print") && j["print"].value("event", 0) >= event;
        }, 120s)) << service_->log();
        return id;
    }

    json heaters(api::ApiClient& c) { return c.call("cell.status")["heaters"]; }

    std::optional<ExternalCell> devices_;
};

}  // namespace

TEST_F(HeaterTest, TheHotendsGoOffWhenAPrintCompletesIsAbortedOrIsGivenUpAfterAFault) {
    start_cell();
    auto c = client();

    const std::int64_t completed = print_until(c, 4);
    EXPECT_TRUE(board_heating());
    // The service sees the heaters on from the board's temperature reports: a report after the
    // print began may still be on its way (seen in CI, the bar's print reaching its fourth event
    // within a second of the start).
    EXPECT_TRUE(eventually([&] {
        const json why = heaters(c).value("why", json());
        return why.is_string() &&
               why.get<std::string>().find("printing job " + std::to_string(completed)) != std::string::npos;
    }, 10s)) << heaters(c).dump();
    const json done = wait_for_state(c, completed, "completed", 180s);
    ASSERT_TRUE(printed(done)) << done.dump(2) << service_->log();
    EXPECT_TRUE(eventually([&] { return board_heaters_off(); }, 10s)) << service_->log();
    EXPECT_TRUE(eventually([&] {
        const json h = heaters(c);
        return !h.value("on", true) && h.value("last_off", json()).is_string();
    }, 10s)) << heaters(c).dump();
    EXPECT_THAT(heaters(c).value("last_off", ""), HasSubstr("job " + std::to_string(completed) + " completed"));

    const std::int64_t aborted = print_until(c, 4);
    EXPECT_TRUE(board_heating());
    ASSERT_EQ(c.call("job.abort", {{"job", aborted}}).value("state", ""), "aborted");
    EXPECT_TRUE(eventually([&] { return board_heaters_off(); }, 10s)) << service_->log();

    // The robot controller lost mid-print: the job holds with the fault, the board stays hot;
    // the operator gives the print up.
    const std::int64_t faulted = print_until(c, 4);
    devices_->kill_robot();
    ASSERT_EQ(wait_for_state(c, faulted, "paused", 60s).value("state", ""), "paused") << service_->log();
    EXPECT_TRUE(board_heating());
    ASSERT_EQ(c.call("job.abort", {{"job", faulted}}).value("state", ""), "aborted");
    EXPECT_TRUE(eventually([&] { return board_heaters_off(); }, 30s)) << service_->log();
}

TEST_F(HeaterTest, AHoldKeepsThemHotForTheNextPrintThenTheyGoOff) {
    start_cell("print: {heater_hold_min: 0.1}\n");  // 6 s
    auto c = client();
    const std::int64_t id = print_until(c, 4);
    ASSERT_EQ(c.call("job.abort", {{"job", id}}).value("state", ""), "aborted");
    ASSERT_TRUE(eventually([&] { return heaters(c).value("why", json()).is_string() &&
                                        heaters(c).value("why", "").find("kept hot") != std::string::npos; },
                           5s)) << heaters(c).dump();
    EXPECT_TRUE(board_heating());
    const json held = heaters(c);
    EXPECT_LE(held.value("off_in_s", 99.0), 6.0) << held.dump();
    EXPECT_TRUE(eventually([&] { return board_heaters_off(); }, 15s)) << service_->log();
    EXPECT_THAT(heaters(c).value("last_off", ""), HasSubstr("print.heater_hold_min"));
}

TEST_F(HeaterTest, AnIdleCellTurnsThemOffAndSoDoesAServiceThatStops) {
    // Killed mid-print, the service leaves the board hot; started again, it finds the cell
    // idle with both heaters on, and turns them off after the idle timeout.
    start_cell("print: {idle_heater_timeout_min: 0.05}\n");  // 3 s
    std::int64_t id = 0;
    {
        auto c = client();
        id = print_until(c, 4);
    }
    service_->kill_now();
    ASSERT_TRUE(board_heating());
    start_service(dir_ / "cell.yaml");
    auto c = client();
    ASSERT_EQ(c.call("job.get", {{"job", id}}).value("state", ""), "interrupted");
    EXPECT_TRUE(eventually([&] { return board_heaters_off(); }, 15s)) << service_->log();
    // The board may read 0 a moment before the service has recorded why it sent the off.
    EXPECT_TRUE(eventually([&] {
        return heaters(c).value("last_off", json()).dump().find("no job on the cell for") != std::string::npos;
    }, 5s)) << heaters(c).dump();
    EXPECT_THAT(service_->log(), HasSubstr("print.heaters_off no job on the cell"));

    // Resumed, then the service is stopped: the job comes back interrupted, the heaters off.
    ASSERT_EQ(c.call("job.resume", {{"job", id}}).value("state", ""), "starting");
    ASSERT_EQ(wait_for_state(c, id, "printing", 120s).value("state", ""), "printing") << service_->log();
    EXPECT_TRUE(eventually([&] { return board_heating(); }, 10s));
    ASSERT_TRUE(service_->terminate(20s)) << service_->log();
    EXPECT_TRUE(board_heaters_off()) << service_->log();
}
