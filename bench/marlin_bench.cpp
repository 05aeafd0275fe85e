// Marlin link protocol overhead: lines per second to the mock GT2560 with immediate oks (pure
// ping-pong over a pseudo-terminal), and the latency from "command requested" (submit) to
// "bytes written" on an idle link, median and p99. Release build; numbers are reported only.
#include "drivers/marlin/marlin_link.hpp"
#include "drivers/sim/mock_board/mock_gt2560.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <vector>

using namespace fibrecell::drivers;
using Clock = std::chrono::steady_clock;

int main() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "marlin-bench-XXXXXX").string();
    const std::filesystem::path dir = mkdtemp(tmpl.data());
    sim::MockGt2560Options mo;
    mo.bootloader_s = 0.01;
    mo.link_path = (dir / "ttyGT2560").string();
    sim::MockGt2560 mock(mo);
    marlin::MarlinLink link;
    marlin::MarlinLinkConfig lc;
    lc.serial.device = mock.port_path();
    link.configure(lc);
    link.activate();

    constexpr int lines = 20000;
    std::vector<std::string> job;
    for (int i = 0; i < lines; ++i) job.push_back("G92 E" + std::to_string(i));
    const auto t0 = Clock::now();
    const auto out = link.submit(job).get();
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    std::printf("throughput: %d lines in %.3f s = %.0f lines/s (%s)\n", lines, s, lines / s,
                out.ok() ? "ok" : "FAILED");

    std::atomic<long long> written_ns{0};
    link.on_bytes_written([&] { written_ns = Clock::now().time_since_epoch().count(); });
    std::vector<double> us;
    for (int i = 0; i < 2000; ++i) {
        written_ns = 0;
        const auto t = Clock::now();
        auto f = link.submit({"M117 lat"});
        f.get();  // idle link before the next sample
        us.push_back((written_ns.load() - t.time_since_epoch().count()) / 1000.0);
    }
    std::sort(us.begin(), us.end());
    std::printf("request->written latency: median %.1f us, p99 %.1f us (n=%zu)\n",
                us[us.size() / 2], us[us.size() * 99 / 100], us.size());
    link.deactivate();
    std::filesystem::remove_all(dir);
    return out.ok() ? 0 : 1;
}
