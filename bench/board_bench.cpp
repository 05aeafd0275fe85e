// The Marlin link against the two simulated boards: the mock GT2560 (in-process, our reading of
// Marlin) and gt2560-avr running the test firmware (real AVR code in simavr, real time). Lines per
// second sustained through the link's window, and request -> ok latency on an idle link, median
// and p99; through gt2560-avr also a feed command -> its first byte on the wire -> the firmware's
// first step pulse (from the simulator's edge log). Release build; numbers are reported only (bench/README.md).
//
//   build/release/bench/board_bench [BUILD_DIR]    BUILD_DIR has tools/gt2560-avr and the firmware
#include "drivers/marlin/marlin_link.hpp"
#include "drivers/sim/mock_gt2560.hpp"
#include "tests/support/piped_process.hpp"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <optional>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace fibrecell::drivers;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

namespace {

void measure(const char* board, const std::string& port) {
    marlin::MarlinLink link;
    marlin::MarlinLinkConfig lc;
    lc.serial.device = port;
    link.configure(lc);
    link.activate();
    constexpr int lines = 5000;
    std::vector<std::string> job;
    for (int i = 0; i < lines; ++i) job.push_back("G92 E" + std::to_string(i % 100));
    const auto t0 = Clock::now();
    const auto out = link.submit(job).get();
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    std::vector<double> ms;
    for (int i = 0; i < 500; ++i) {
        const auto t = Clock::now();
        link.submit({"G92 E0"}).get();
        ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t).count());
    }
    std::sort(ms.begin(), ms.end());
    std::printf("%-22s %8.0f lines/s (%d lines, %s)   request->ok median %.2f ms, p99 %.2f ms\n", board,
                lines / s, lines, out.ok() ? "all ok" : "FAILED", ms[ms.size() / 2],
                ms[ms.size() * 99 / 100]);
    link.deactivate();
}

double sim_time_of(const std::string& status) {
    const auto at = status.find("\"sim_time_s\":");
    return at == std::string::npos ? -1 : std::strtod(status.c_str() + at + 13, nullptr);
}

// The simulator's clock against the host's: a status answer's sim_time_s taken at the middle of
// its round trip (off by at most half of it, printed).
struct ClockMap {
    double offset_s = 0;  // host seconds (since t_ref) - simulated seconds
    double half_rtt_ms = 0;
};

ClockMap map_clock(fibrecell::test::PipedProcess& board, Clock::time_point t_ref) {
    const auto q0 = Clock::now();
    board.write_line("status");
    const auto st = board.read_line_starting("status ", std::chrono::seconds(10));
    const auto q1 = Clock::now();
    const double mid = std::chrono::duration<double>(q0 - t_ref).count() +
                       std::chrono::duration<double>(q1 - q0).count() / 2;
    return {mid - sim_time_of(st.value_or("")),
            std::chrono::duration<double, std::milli>(q1 - q0).count() / 2};
}

// The first `e1_step 1` edge in the lines added to the edge log since the last call.
std::optional<double> next_step_edge(std::ifstream& edges) {
    std::optional<double> first;
    std::string line;
    edges.clear();
    while (std::getline(edges, line)) {
        double t = 0;
        char pin[32] = {};
        int level = 0;
        if (std::sscanf(line.c_str(), "%lf %31s %d", &t, pin, &level) == 3 &&
            std::string(pin) == "e1_step" && level == 1 && !first)
            first = t;
    }
    return first;
}

// Through gt2560-avr: a feed command given to the link -> its first byte on the wire -> the
// firmware's first E1 step pulse, per move (the CCF hotend hot, one 0.5 mm move at 5 mm/s at a
// time, the link idle before each).
void measure_step_start(fibrecell::test::PipedProcess& board, const std::string& port,
                        const fs::path& edge_log) {
    marlin::MarlinLink link;
    marlin::MarlinLinkConfig lc;
    lc.serial.device = port;
    const auto t_ref = Clock::now();
    std::atomic<double> wire_s{-1};
    link.on_bytes_written([&] {
        double none = -1;
        wire_s.compare_exchange_strong(none, std::chrono::duration<double>(Clock::now() - t_ref).count());
    });
    link.configure(lc);
    link.activate();
    if (!link.submit({"M83", "T1", "M104 T1 S200", "M109 T1 S200"}).get().ok()) {
        std::printf("gt2560-avr: heating failed\n");
        return;
    }
    std::ifstream edges(edge_log);
    next_step_edge(edges);  // what came before
    std::vector<double> to_wire, to_step;
    double worst_half_rtt = 0;
    for (int i = 0; i < 40; ++i) {
        const ClockMap map = map_clock(board, t_ref);
        worst_half_rtt = std::max(worst_half_rtt, map.half_rtt_ms);
        wire_s = -1;
        const double t0 = std::chrono::duration<double>(Clock::now() - t_ref).count();
        link.submit({"G1 E0.5 F300", "M400"}).get();
        map_clock(board, t_ref);  // flushes the edge log
        const auto step = next_step_edge(edges);
        if (!step || wire_s < 0) continue;
        to_wire.push_back(1e3 * (wire_s - t0));
        to_step.push_back(1e3 * (*step + map.offset_s - t0));
    }
    link.deactivate();
    if (to_step.empty()) {
        std::printf("gt2560-avr: no step pulses seen\n");
        return;
    }
    const auto median = [](std::vector<double> v) { std::sort(v.begin(), v.end()); return v[v.size() / 2]; };
    const auto p99 = [](std::vector<double> v) { std::sort(v.begin(), v.end()); return v[v.size() * 99 / 100]; };
    std::printf("%-22s command->first byte median %.3f ms, p99 %.3f ms; command->first E1 step "
                "median %.2f ms, p99 %.2f ms (%zu moves; MCU clock mapped within %.2f ms)\n",
                "gt2560-avr (test fw)", median(to_wire), p99(to_wire), median(to_step),
                p99(to_step), to_step.size(), worst_half_rtt);
}

}  // namespace

int main(int argc, char** argv) {
    const std::string build = argc > 1 ? argv[1] : FIBRECELL_BINARY_DIR;
    std::string tmpl = (fs::temp_directory_path() / "board-bench-XXXXXX").string();
    const fs::path dir = mkdtemp(tmpl.data());
    {
        sim::MockGt2560Options mo;
        mo.bootloader_s = 0.01;
        mo.link_path = (dir / "ttyMock").string();
        sim::MockGt2560 mock(mo);
        measure("mock-gt2560", mock.port_path());
    }
    const std::string tool = build + "/tools/gt2560-avr";
    const std::string firmware = build + "/tests/firmware/gt2560-test-firmware.elf";
    if (!fs::exists(tool) || !fs::exists(firmware)) {
        std::printf("gt2560-avr: not built in %s (libsimavr-dev, gcc-avr)\n", build.c_str());
    } else {
        fibrecell::test::PipedProcess board(tool, {firmware, "--link", (dir / "ttyAvr").string(),
                                                   "--edge-log", (dir / "edges.log").string()});
        if (board.read_line_starting("port ", std::chrono::seconds(20))) {
            measure("gt2560-avr (test fw)", (dir / "ttyAvr").string());
            measure_step_start(board, (dir / "ttyAvr").string(), dir / "edges.log");
        }
        board.write_line("status");
        if (const auto st = board.read_line_starting("status ", std::chrono::seconds(10)))
            std::printf("gt2560-avr status: %.300s\n", st->c_str());
        board.write_line("quit");
        board.wait(std::chrono::seconds(10));
    }
    fs::remove_all(dir);
    return 0;
}
