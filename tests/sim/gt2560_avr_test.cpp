// gt2560-avr, the board simulator for real AVR firmware, proved against known answers with the
// project's own test firmware (tests/firmware, built with gcc-avr): its UART both ways (with
// simavr 1.6's UDRE work-around), the thermal model through ADC8/ADC9, step pulses counted into
// millimetres at the feed rate, the cutter and servo pin, real-time pacing, wire faults, a pause,
// unplugging and an MCU reset. The tool runs as its own process on a real pseudo-terminal; the
// host side here writes and reads that pty as a driver would.
#include "tests/support/piped_process.hpp"
#include "tests/support/eventually.hpp"
#include "tests/support/fd_lines.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/project_paths.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

// Its own namespace: compiled in a batch with the other simulator tests, whose helpers share names.
namespace sim_gt2560_avr_test {

using namespace std::chrono_literals;
using fibrecell::test::PipedProcess;
using fibrecell::test::TempDir;
using Json = nlohmann::json;

namespace {

const std::string tool = fibrecell::test::binary_path("tools/gt2560-avr");
const std::string firmware_elf =
    fibrecell::test::binary_path("tests/firmware/gt2560-test-firmware.elf");
const std::string firmware_hex =
    fibrecell::test::binary_path("tests/firmware/gt2560-test-firmware.hex");
// Built as the Geeetech example configures stock Marlin: E direction inverted, PID heaters.
const std::string geeetech_elf =
    fibrecell::test::binary_path("tests/firmware/gt2560-test-firmware-geeetech.elf");

// The host end of the board's USB serial port: raw bytes, lines with a deadline.
class Host {
  public:
    explicit Host(const std::string& port) {
        fd_ = ::open(port.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
        if (fd_ < 0) throw std::runtime_error("cannot open " + port);
        lines_ = fibrecell::test::FdLines(fd_);
        termios t{};
        ::tcgetattr(fd_, &t);
        ::cfmakeraw(&t);
        ::tcsetattr(fd_, TCSANOW, &t);
    }
    ~Host() { ::close(fd_); }
    Host(const Host&) = delete;
    Host& operator=(const Host&) = delete;

    void send(const std::string& line) {
        const std::string l = line + "\n";
        ASSERT_EQ(::write(fd_, l.data(), l.size()), static_cast<ssize_t>(l.size()));
    }
    // "N<n> <cmd>*<xor of the bytes before *>", as Marlin's hosts frame a line.
    static std::string numbered(long n, const std::string& cmd) {
        std::string s = "N" + std::to_string(n) + " " + cmd;
        int sum = 0;
        for (char c : s) sum ^= static_cast<unsigned char>(c);
        return s + "*" + std::to_string(sum);
    }
    // The next line, or nothing within `timeout` (or when the port closed).
    std::optional<std::string> line(std::chrono::milliseconds timeout = 10s) { return lines_.next(timeout); }
    // Lines up to and including the first that starts with `prefix`; empty if it never comes.
    std::vector<std::string> until(const std::string& prefix, std::chrono::milliseconds timeout = 20s) {
        std::vector<std::string> lines;
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        for (;;) {
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                deadline - std::chrono::steady_clock::now());
            const auto l = line(std::max(left, 0ms));
            if (!l) return {};
            lines.push_back(*l);
            if (l->rfind(prefix, 0) == 0) return lines;
        }
    }
    // Sends a command and returns its answer lines up to its ok.
    std::vector<std::string> command(const std::string& cmd, std::chrono::milliseconds timeout = 20s) {
        send(cmd);
        return until("ok", timeout);
    }

  private:
    int fd_ = -1;
    fibrecell::test::FdLines lines_;
};

bool contains(const std::vector<std::string>& lines, const std::string& text) {
    for (const auto& l : lines)
        if (l.find(text) != std::string::npos) return true;
    return false;
}

// The tool with the test firmware, a fast-heating cell (C = 0.5 J/K: 25 -> 200 C in about 3 s),
// and its edge log, in a folder of its own.
class Gt2560Avr : public ::testing::Test {
  protected:
    void SetUp() override {
        if (!std::filesystem::exists(tool) || !std::filesystem::exists(firmware_elf))
            GTEST_SKIP() << "gt2560-avr or the test firmware is not built (libsimavr-dev, gcc-avr)";
        std::ofstream(dir.path() / "cell.yaml")
            << "simulated: true\nsimulation:\n  heater_power_w: 40\n  heater_loss_w_per_k: 0.12\n"
               "  heat_capacity_j_per_k: 0.5\n  ambient_c: 25\n";
    }

    void start(const std::string& firmware = firmware_elf, std::vector<std::string> extra = {}) {
        std::vector<std::string> args{firmware, "--link", port(), "--cell",
                                      (dir.path() / "cell.yaml").string(), "--edge-log",
                                      (dir.path() / "edges.log").string()};
        args.insert(args.end(), extra.begin(), extra.end());
        board.emplace(tool, args);
        ASSERT_TRUE(board->read_line_starting("port ", 20s)) << board->read_stderr();
        host.emplace(port());
        ASSERT_FALSE(host->until("start").empty()) << "no boot line";
    }

    std::string port() const { return (dir.path() / "ttyGT2560").string(); }

    Json status() {
        board->write_line("status");
        const auto s = board->read_line_starting("status ", 10s);
        if (!s) throw std::runtime_error("no status from gt2560-avr");
        return Json::parse(*s);
    }

    void control(const std::string& cmd) {
        board->write_line(cmd);
        const auto word = cmd.substr(0, cmd.find(' '));
        ASSERT_TRUE(board->read_line_starting("done " + word, 10s)) << cmd;
    }

    // Heats T0 to 200 C and waits for M109's ok.
    void heat_t0() { ASSERT_FALSE(host->command("M109 T0 S200", 30s).empty()) << "M109 timed out"; }

    TempDir dir{"gt2560-avr"};
    std::optional<PipedProcess> board;
    std::optional<Host> host;
};

}  // namespace

TEST_F(Gt2560Avr, BootsAndSpeaksMarlinsLineProtocol) {
    start();
    const auto caps = host->command("M115");
    EXPECT_TRUE(contains(caps, "FIRMWARE_NAME:fibrecell-test-firmware"));
    EXPECT_TRUE(contains(caps, "EXTRUDER_COUNT:2"));
    ASSERT_EQ(host->command(Host::numbered(1, "M110 N1")).back(), "ok");
    // A bad checksum, then a skipped number: an error, Resend of the next line, ok.
    std::string bad = Host::numbered(2, "M105");
    bad.back() = bad.back() == '0' ? '1' : '0';
    EXPECT_EQ(host->command(bad), (std::vector<std::string>{
                                      "Error:checksum mismatch, Last Line: 1", "Resend: 2", "ok"}));
    EXPECT_EQ(host->command(Host::numbered(3, "M105")),
              (std::vector<std::string>{"Error:Line Number is not Last Line Number+1, Last Line: 1",
                                        "Resend: 2", "ok"}));
    const auto report = host->command(Host::numbered(2, "M105"));
    ASSERT_EQ(report.size(), 1u);
    EXPECT_EQ(report[0].rfind("ok T:", 0), 0u) << report[0];
    // The hotends start at ambient, read back through the thermistor model and the ADC.
    EXPECT_NE(report[0].find("T0:25."), std::string::npos) << report[0];
}

TEST_F(Gt2560Avr, HeatsThroughTheThermalModelAsItsClosedForm) {
    start();
    heat_t0();
    // M109 ends within a degree of the target; the heater goes off at the next sample at 200 C.
    ASSERT_TRUE(fibrecell::test::eventually(
        [&] { return !status()["hotends"][0]["heater_on"].get<bool>(); }, 10s, 20ms));
    const Json s = status();  // also flushes the edge log
    // The bang-bang firmware switches the heater on at a 100 ms sample and off at the first sample
    // at or above 200 C, so its first on-time is the model's 25 -> 200 C at full power,
    // -C/k ln(1 - 175 k/P) = 3.10 s, plus less than one sample. Measured on the MCU's own clock
    // (the edge log), not the host's, which a loaded machine delays.
    std::ifstream log(dir.path() / "edges.log");
    double t = 0, on = -1, off = -1;
    std::string pin;
    int level = 0;
    while (log >> t >> pin >> level && off < 0) {
        if (pin != "heater0") continue;
        if (level == 1 && on < 0) on = t;
        else if (level == 0 && on >= 0) off = t;
    }
    ASSERT_GE(on, 0) << "the heater never came on";
    ASSERT_GE(off, 0) << "the heater never went off";
    const double expected = -0.5 / 0.12 * std::log(1 - 175 * 0.12 / 40);
    EXPECT_GE(off - on, expected - 0.002);
    EXPECT_LE(off - on, expected + 0.1 + 0.002);
    // Bang-bang sampled every 100 ms swings by what the block gains or loses in that time: at
    // 200 C it loses 0.12 x 175 = 21 W, 42 K/s on 0.5 J/K, so within 1 + 4.2 K of the target.
    const double swing = 1 + 0.1 * 0.12 * 175 / 0.5;
    EXPECT_NEAR(s["hotends"][0]["temp_c"].get<double>(), 200, swing);
    EXPECT_NEAR(s["hotends"][1]["temp_c"].get<double>(), 25, 0.01);  // T1 never heated
    // It holds there: two seconds later, still within the swing.
    const double hold_from = s["sim_time_s"];
    ASSERT_TRUE(fibrecell::test::eventually([&] { return status()["sim_time_s"].get<double>() > hold_from + 2; }));
    EXPECT_NEAR(status()["hotends"][0]["temp_c"].get<double>(), 200, swing);
}

TEST_F(Gt2560Avr, CountsStepPulsesIntoMillimetresAtTheFeedRate) {
    start();
    host->command("M83");
    // Cold: Marlin's refusal, and no pulse.
    EXPECT_TRUE(contains(host->command("G1 E5 F600"), "echo: cold extrusion prevented"));
    heat_t0();
    EXPECT_EQ(status()["extruders"][0]["steps"], 0);
    host->command("G1 E10.5 F600");
    host->command("G1 E-2 F600");
    host->command("M400");
    const Json e0 = status()["extruders"][0];
    EXPECT_EQ(e0["forward"], 1103);   // 10.5 mm x 105, rounded
    EXPECT_EQ(e0["backward"], 210);
    EXPECT_NEAR(e0["mm"].get<double>(), 893.0 / 105, 1e-9);
    EXPECT_EQ(e0["while_disabled"], 0);
    // 1313 pulses at 10 mm/s = 1050 steps/s, back to back: 1312 intervals of 1/1050 s.
    EXPECT_NEAR(e0["last_step_s"].get<double>() - e0["first_step_s"].get<double>(), 1312.0 / 1050, 2e-3);
    EXPECT_EQ(status()["extruders"][1]["steps"], 0);
    // T1 drives E1 only.
    host->command("M109 T1 S200", 30s);
    EXPECT_TRUE(contains(host->command("T1"), "echo:Active Extruder: 1"));
    host->command("G1 E1 F300");
    host->command("M400");
    EXPECT_EQ(status()["extruders"][1]["steps"], 105);
    EXPECT_EQ(status()["extruders"][0]["forward"], 1103);
}

TEST_F(Gt2560Avr, RecordsTheCutterPinAndServoPulsesWithTheirTimes) {
    start();
    // Sent together, as the cut is (the firmware's ring holds them): the pin's timing is then
    // the MCU's alone, not the host's round trips.
    host->send("M42 P11 S255\nG4 P200\nM42 P11 S0");
    for (int i = 0; i < 3; ++i) ASSERT_FALSE(host->until("ok").empty());
    Json d11 = status()["d11"];
    ASSERT_EQ(d11["edges"].size(), 2u);
    EXPECT_EQ(d11["edges"][0][1], 1);
    EXPECT_EQ(d11["edges"][1][1], 0);
    // G4 P200 between the two: the pin was high for 200 ms of the MCU's time (+ two commands).
    const double held = d11["edges"][1][0].get<double>() - d11["edges"][0][0].get<double>();
    EXPECT_GT(held, 0.199);  // the dwell counts the firmware's 1 ms ticks from mid-tick
    EXPECT_LT(held, 0.215);
    host->command("M280 P0 S90");
    ASSERT_TRUE(fibrecell::test::eventually([&] { return status()["d11"]["servo_pulse_us"].get<double>() > 0; }));
    EXPECT_NEAR(status()["d11"]["servo_pulse_us"].get<double>(), 544 + (2400 - 544) / 2.0, 2);
    // The edge log has every edge with its time, in order.
    std::ifstream log(dir.path() / "edges.log");
    double t = -1, last = -1;
    std::string pin;
    int level = 0, d11_edges = 0;
    while (log >> t >> pin >> level) {
        EXPECT_GE(t, last);
        last = t;
        d11_edges += pin == "d11";
    }
    EXPECT_GE(d11_edges, 4);
}

TEST_F(Gt2560Avr, RunsAtRealTimeAndNeverFaster) {
    start();
    const Json before = status();
    const auto wall0 = std::chrono::steady_clock::now();
    host->command("G4 P1500");
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    const Json after = status();
    const double sim = after["sim_time_s"].get<double>() - before["sim_time_s"].get<double>();
    // The dwell counts 1 ms ticks from mid-tick, the MCU runs at most one 0.25 ms slice ahead of
    // the wall clock, and a lag of under 5 ms when the dwell began (a busy machine) is caught up
    // by running faster (more is written off): its 1.5 s took at least 1.5 s of ours, less those
    // 6.25 ms (1.49787 s seen with three tests beside it on 2 cores).
    EXPECT_GE(sim, 1.499);
    EXPECT_GE(wall, 1.4935);
    // Behind (a loaded machine), it writes the lag off instead of rushing, and says so.
    const double written_off = after["behind"]["written_off_s"].get<double>() -
                               before["behind"]["written_off_s"].get<double>();
    EXPECT_LE(sim, wall + 0.05 - written_off + 0.05);
}

TEST_F(Gt2560Avr, CorruptedLinesAreResentAndEachRunsOnce) {
    start();
    control("fault to-board line 0.2");
    host->command(Host::numbered(0, "M110 N0"));
    int errors = 0, reports = 0;
    long n = 1;
    while (n <= 40) {
        host->send(Host::numbered(n, "M105"));
        // Until this line's ok: a report ("ok T:") means it ran; an error and "Resend: k" mean
        // the board wants line k again.
        std::optional<long> resend;
        for (;;) {
            const auto l = host->line(10s);
            ASSERT_TRUE(l) << "no answer to line " << n;
            if (l->rfind("Error:", 0) == 0) ++errors;
            if (l->rfind("Resend: ", 0) == 0) resend = std::stol(l->substr(8));
            if (l->rfind("ok T:", 0) == 0) {
                ++reports;
                ++n;
                break;
            }
            if (*l == "ok") {
                if (resend) n = *resend;
                break;
            }
        }
    }
    const Json wire = status()["wire"]["to_board"];
    EXPECT_EQ(reports, 40);  // every line ran exactly once
    EXPECT_GT(wire["lines_corrupted"].get<int>(), 0);
    EXPECT_EQ(errors, wire["lines_corrupted"].get<int>());  // one error (and resend) each
    control("fault off");
    // The other way: with every byte from the board dropped nothing arrives, then all is well.
    control("fault from-board drop 1");
    host->send("M105");
    EXPECT_FALSE(host->line(500ms));
    control("fault off");
    const auto after = host->command("M105");
    EXPECT_FALSE(after.empty()) << status().dump();
}

TEST_F(Gt2560Avr, APauseStopsTheMcuClockAndItGoesOnAfter) {
    start();
    const double sim0 = status()["sim_time_s"];
    const auto wall0 = std::chrono::steady_clock::now();
    control("pause 1");
    const auto answer = host->command("M105");
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    ASSERT_FALSE(answer.empty());
    EXPECT_GE(wall, 1.0);  // no answer while the MCU stood still
    const Json s = status();
    EXPECT_DOUBLE_EQ(s["paused_s"].get<double>(), 1.0);
    EXPECT_LT(s["sim_time_s"].get<double>() - sim0, wall - 0.9);
}

TEST_F(Gt2560Avr, UnpluggedThePortClosesAndReplugGivesTheSameBoard) {
    start();
    host->command("M104 T0 S150");
    control("unplug");
    EXPECT_FALSE(host->line(5s));  // EOF: the cable is out
    EXPECT_FALSE(std::filesystem::exists(port()));
    control("replug");
    ASSERT_TRUE(std::filesystem::exists(port()));
    host.emplace(port());
    const auto report = host->command("M105");
    ASSERT_FALSE(report.empty());
    EXPECT_NE(report.back().find("T0:"), std::string::npos);
    EXPECT_NE(report.back().find("/150.0"), std::string::npos) << report.back();  // no reset
}

TEST_F(Gt2560Avr, AResetRebootsTheMcuButTheHotendStaysHot) {
    start();
    heat_t0();
    control("reset");
    ASSERT_FALSE(host->until("start").empty()) << "no boot line after the reset";
    EXPECT_EQ(status()["resets"], 1);
    const auto report = host->command("M105");
    ASSERT_FALSE(report.empty());
    // The firmware forgot its target; the metal did not cool in a moment.
    EXPECT_NE(report.back().find(" /0.0"), std::string::npos) << report.back();
    EXPECT_GT(status()["hotends"][0]["temp_c"].get<double>(), 190);
}

// A firmware built with INVERT_E0_DIR/INVERT_E1_DIR (dir low = forward): read as the default
// convention, every feed counts backwards; with --invert-e-dir, forwards.
TEST_F(Gt2560Avr, AnInvertedDirectionBuildFeedsForwardOnlyWhenTheSimulatorIsToldSo) {
    for (const bool told : {false, true}) {
        SCOPED_TRACE(told ? "--invert-e-dir" : "default convention");
        start(geeetech_elf, told ? std::vector<std::string>{"--invert-e-dir"} : std::vector<std::string>{});
        host->command("M83");
        ASSERT_FALSE(host->command("M109 T1 S200", 60s).empty()) << "M109 timed out";
        host->command("T1");
        host->command("G1 E10 F600");
        host->command("M400");
        EXPECT_NEAR(status()["extruders"][1]["mm"].get<double>(), told ? 10.0 : -10.0, 1e-9);
        host.reset();
        board->write_line("quit");
        ASSERT_EQ(board->wait(10s), 0) << board->read_stderr();
    }
}

// Marlin's heating watchdog (the test firmware's default build: 2 C in 5 s, so that this takes
// seconds): a hotend that does not heat (a cartridge of 0.05 W) halts the firmware with Marlin's
// words, heaters off, and it answers nothing more until a reset.
TEST_F(Gt2560Avr, TheHeatingWatchdogHaltsAHotendThatDoesNotHeatUntilAReset) {
    std::ofstream(dir.path() / "cell.yaml")
        << "simulated: true\nsimulation: {heater_power_w: 0.05, heat_capacity_j_per_k: 0.5}\n";
    start();
    host->send("M104 T1 S250");
    const auto lines = host->until("Error:Printer halted", 30s);
    ASSERT_FALSE(lines.empty()) << "no halt";
    EXPECT_TRUE(contains(lines, "Error:Heating failed, system stopped! Heater_ID: 1"));
    const Json s = status();
    EXPECT_FALSE(s["hotends"][1]["heater_on"].get<bool>());
    EXPECT_LT(s["hotends"][1]["temp_c"].get<double>(), 30);
    host->send("M105");
    EXPECT_FALSE(host->line(1s)) << "a halted firmware answered";
    control("reset");
    ASSERT_FALSE(host->until("start").empty()) << "no boot line after the reset";
    EXPECT_FALSE(host->command("M105").empty());
}

TEST_F(Gt2560Avr, LoadsIntelHexTooAndQuitsCleanly) {
    start(firmware_hex);
    EXPECT_TRUE(contains(host->command("M115"), "EXTRUDER_COUNT:2"));
    board->write_line("quit");
    EXPECT_EQ(board->wait(10s), 0) << board->read_stderr();  // under ASan: no leak either
}

TEST_F(Gt2560Avr, ABadFirmwareFileIsRefusedByName) {
    PipedProcess missing(tool, {(dir.path() / "nope.elf").string()});
    EXPECT_EQ(missing.wait(10s), 1);
    EXPECT_NE(missing.read_stderr().find("no firmware file"), std::string::npos);
    std::ofstream(dir.path() / "text.elf") << "not firmware\n";
    PipedProcess text(tool, {(dir.path() / "text.elf").string()});
    EXPECT_EQ(text.wait(10s), 1);
    EXPECT_NE(text.read_stderr().find("is not an AVR ELF file"), std::string::npos);
}

}  // namespace sim_gt2560_avr_test
