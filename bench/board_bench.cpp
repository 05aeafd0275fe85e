// The Marlin link against the two simulated boards: the mock GT2560 (in-process, our reading of
// Marlin) and gt2560-avr running the test firmware (real AVR code in simavr, real time). Lines per
// second sustained through the link's window, and request -> ok latency on an idle link, median
// and p99. Release build; numbers are reported only (bench/README.md).
//
//   build/release/bench/board_bench [BUILD_DIR]    BUILD_DIR has tools/gt2560-avr and the firmware
#include "drivers/marlin/marlin_link.hpp"
#include "drivers/sim/mock_gt2560.hpp"
#include "tests/support/piped_process.hpp"

#include <algorithm>
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
        fibrecell::test::PipedProcess board(tool, {firmware, "--link", (dir / "ttyAvr").string()});
        if (board.read_line_starting("port ", std::chrono::seconds(20)))
            measure("gt2560-avr (test fw)", (dir / "ttyAvr").string());
        board.write_line("status");
        if (const auto st = board.read_line_starting("status ", std::chrono::seconds(10)))
            std::printf("gt2560-avr status: %.300s\n", st->c_str());
        board.write_line("quit");
        board.wait(std::chrono::seconds(10));
    }
    fs::remove_all(dir);
    return 0;
}
