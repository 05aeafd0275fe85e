// Robot I/O link latency over loopback Modbus TCP (docs/robot-io.md): from the simulated robot
// changing the event counter in the server (RobotIoServer::set_event_number) to the link's
// on_event callback, median and p99, at several poll periods; and from set_release() to the server
// seeing the new barrier release. Changes come at random phases relative to the poll, as a robot's
// events do. Release build; numbers are reported only.
#include "drivers/abb/modbus/robot_io_link.hpp"
#include "drivers/sim/robot_io/robot_io_server.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <random>
#include <thread>
#include <vector>

using namespace fibrecell::drivers::abb;
using fibrecell::drivers::sim::RobotIoServer;
using fibrecell::drivers::sim::ServiceCommands;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

namespace {

struct Summary {
    double median_us = 0, p99_us = 0, max_us = 0;
};

Summary summarise(std::vector<double> us) {
    std::sort(us.begin(), us.end());
    return {us[us.size() / 2], us[us.size() * 99 / 100], us.back()};
}

void run(const char* label, std::chrono::microseconds poll, int stable_reads, int samples) {
    RobotIoServer server(RobotIoMap{});
    RobotIoConfig c;
    c.host = server.host();
    c.port = server.port();
    c.poll_period = poll;
    c.stable_reads = stable_reads;
    c.stats_log_period = 0s;

    std::atomic<std::uint16_t> want{0}, want_release{0};
    std::atomic<Clock::rep> seen_at{0}, released_at{0};
    server.on_commands([&](const ServiceCommands& s) {
        if (s.release == want_release.load()) released_at = Clock::now().time_since_epoch().count();
    });
    RobotIoLink link(c);
    link.on_event([&](const EventCounterChange& e) {
        if (e.value == want.load()) seen_at = Clock::now().time_since_epoch().count();
    });
    link.start();
    if (!link.wait_until_up(5000ms)) {
        std::printf("%s: link not up: %s\n", label, link.snapshot().last_error.c_str());
        return;
    }

    std::mt19937 rng(42);
    std::uniform_int_distribution<long long> phase(0, 2 * poll.count());
    std::vector<double> event_us, release_us;
    int lost = 0;
    for (int i = 1; i <= samples; ++i) {
        std::this_thread::sleep_for(std::chrono::microseconds(phase(rng)));
        const auto n = static_cast<std::uint16_t>(i);
        want = n;
        seen_at = 0;
        const auto t0 = Clock::now();
        server.set_event_number(n);
        while (seen_at.load() == 0 && Clock::now() - t0 < 1s) std::this_thread::sleep_for(20us);
        if (seen_at.load() == 0) {
            ++lost;
            continue;
        }
        event_us.push_back(static_cast<double>(seen_at.load() - t0.time_since_epoch().count()) /
                           1e3);

        // Output path: set_release() -> written -> the server has it (every 4th sample).
        if (i % 4 == 0) {
            want_release = n;
            released_at = 0;
            const auto t1 = Clock::now();
            link.set_release(n);
            while (released_at.load() == 0 && Clock::now() - t1 < 1s)
                std::this_thread::sleep_for(20us);
            if (released_at.load() != 0)
                release_us.push_back(
                    static_cast<double>(released_at.load() - t1.time_since_epoch().count()) / 1e3);
        }
    }
    const auto snap = link.snapshot();
    link.stop();
    server.on_commands(nullptr);
    if (event_us.empty()) {
        std::printf("%s: no samples\n", label);
        return;
    }
    const Summary e = summarise(event_us);
    std::printf(
        "%-28s event->callback median %7.0f us  p99 %7.0f us  max %7.0f us  (n=%zu, lost %d)\n",
        label, e.median_us, e.p99_us, e.max_us, event_us.size(), lost);
    if (!release_us.empty()) {
        const Summary r = summarise(release_us);
        std::printf("%-28s set_release->server median %7.0f us  p99 %7.0f us  (n=%zu)\n", "",
                    r.median_us, r.p99_us, release_us.size());
    }
    std::printf("%-28s poll cycle (2 reads) last %.0f us, max %.0f us; faults %llu\n", "",
                snap.stats.poll_us_last, snap.stats.poll_us_max,
                static_cast<unsigned long long>(snap.stats.faults));
}

}  // namespace

int main() {
    spdlog::set_level(spdlog::level::warn);
    constexpr int samples = 1500;
    run("poll 2 ms, stable_reads 1", 2000us, 1, samples);
    run("poll 1 ms, stable_reads 1", 1000us, 1, samples);
    run("poll 2 ms, stable_reads 2", 2000us, 2, samples);
    run("poll 1 ms, stable_reads 2", 1000us, 2, samples);
    return 0;
}
