// The Marlin link against the two simulated boards: the mock GT2560 (in-process, our reading of
// Marlin) and gt2560-avr running the test firmware (real AVR code in simavr, real time). Lines per
// second sustained through the link's window, and request -> ok latency on an idle link, median
// and p99; through gt2560-avr also a feed command -> its first byte on the wire -> the firmware's
// first step pulse (from the simulator's edge log). Release build; numbers are reported only (bench/README.md).
//
//   build/release/bench/board_bench [BUILD_DIR]    BUILD_DIR has tools/gt2560-avr and the firmware
#include "drivers/marlin/marlin_link.hpp"
#include "drivers/sim/mock_board/mock_gt2560.hpp"
#include "gt2560_avr_process.hpp"
#include "tests/support/project_paths.hpp"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <optional>
#include <chrono>
#include <cstdio>
#include <filesystem>
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

// Through gt2560-avr: a feed command given to the link -> its first byte on the wire -> the
// firmware's first E1 step pulse, per move (the CCF hotend hot, one 0.5 mm move at 5 mm/s at a
// time, the link idle before each).
void measure_step_start(fibrecell::bench::Gt2560AvrProcess& board) {
    marlin::MarlinLink link;
    marlin::MarlinLinkConfig lc;
    lc.serial.device = board.port();
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
    board.status();
    board.new_edges();  // what came before
    std::vector<double> to_wire, to_step;
    double worst_half_rtt = 0;
    for (int i = 0; i < 40; ++i) {
        const auto map = board.map_clock(t_ref);
        worst_half_rtt = std::max(worst_half_rtt, map.half_rtt_ms);
        wire_s = -1;
        const double t0 = std::chrono::duration<double>(Clock::now() - t_ref).count();
        link.submit({"G1 E0.5 F300", "M400"}).get();
        board.status();  // flushes the edge log
        std::optional<double> step;
        for (const auto& e : board.new_edges())
            if (!step && e.pin == "e1_step" && e.level == 1) step = e.t_s;
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
    const std::string build = argc > 1 ? argv[1] : fibrecell::test::binary_path();
    std::string tmpl = (fs::temp_directory_path() / "board-bench-XXXXXX").string();
    const fs::path dir = mkdtemp(tmpl.data());
    {
        sim::MockGt2560Options mo;
        mo.bootloader_s = 0.01;
        mo.link_path = (dir / "ttyMock").string();
        sim::MockGt2560 mock(mo);
        measure("mock-gt2560", mock.port_path());
    }
    {
        fibrecell::bench::Gt2560AvrProcess board(build, dir);
        if (board.port().empty()) {
            std::printf("gt2560-avr: not built in %s (libsimavr-dev, gcc-avr), or it did not start\n",
                        build.c_str());
        } else {
            measure("gt2560-avr (test fw)", board.port());
            measure_step_start(board);
            std::printf("gt2560-avr status: %.300s\n", board.status().c_str());
        }
    }
    fs::remove_all(dir);
    return 0;
}
