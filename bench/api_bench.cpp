// Socket API overhead: calls per second of a trivial method over the Unix socket from one
// client, one call at a time (round trip, with median and p99 latency) and pipelined (a window
// of requests in flight, as a busy script would). Also a subscriber's delivery of in-order events.
// Release build; numbers are reported only.
#include "daemon/api/api_client.hpp"
#include "daemon/api/api_server.hpp"

#include <spdlog/spdlog.h>
#include <boost/asio/executor_work_guard.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

using namespace fibrecell::api;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

int main() {
    spdlog::set_level(spdlog::level::warn);
    std::string tmpl = (std::filesystem::temp_directory_path() / "api-bench-XXXXXX").string();
    const std::filesystem::path dir = mkdtemp(tmpl.data());
    ApiConfig config;
    config.socket_path = (dir / "api.sock").string();

    boost::asio::io_context io;
    auto work = boost::asio::make_work_guard(io);
    ApiServer server(io, config);
    server.add_method("ping", [](const json&, const CallContext&) { return json{{"pong", true}}; });
    server.start();
    std::thread io_thread([&] { io.run(); });

    auto client = ApiClient::connect({.socket_path = config.socket_path});
    for (int i = 0; i < 1000; ++i) client.call("ping");  // warm-up

    // One call at a time.
    constexpr int kCalls = 50000;
    std::vector<double> us;
    us.reserve(kCalls);
    const auto t0 = Clock::now();
    for (int i = 0; i < kCalls; ++i) {
        const auto t = Clock::now();
        client.call("ping");
        us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t).count());
    }
    const double s = seconds_since(t0);
    std::sort(us.begin(), us.end());
    std::printf(
        "round trip: %d calls in %.3f s = %.0f calls/s; latency median %.1f us, p99 %.1f us\n",
        kCalls, s, kCalls / s, us[us.size() / 2], us[us.size() * 99 / 100]);

    // Pipelined: windows of 64 requests written at once, then their 64 answers read.
    constexpr int kWindow = 64;
    constexpr int kWindows = 2000;
    std::string window;
    for (int i = 0; i < kWindow; ++i)
        window += R"({"jsonrpc":"2.0","id":)" + std::to_string(i) + R"(,"method":"ping"})" + "\n";
    int answered = 0;
    const auto t1 = Clock::now();
    for (int w = 0; w < kWindows; ++w) {
        client.send_line(window);
        for (int i = 0; i < kWindow; ++i)
            if (client.read_message(std::chrono::seconds(10))) ++answered;
    }
    const double s1 = seconds_since(t1);
    std::printf("pipelined (window %d): %d calls in %.3f s = %.0f calls/s\n", kWindow, answered, s1,
                answered / s1);

    // Events: one subscriber, in-order notifications published from another thread.
    auto subscriber = ApiClient::connect({.socket_path = config.socket_path});
    subscriber.call("subscribe", {{"topics", {"j-1"}}});
    constexpr int kEvents = 50000;
    const auto t2 = Clock::now();
    std::thread publisher([&] {
        for (int i = 0; i < kEvents; ++i)
            server.publish({"j-1", notify::log, {{"seq", i}, {"text", "layer 12 path 3 done"}}});
    });
    int received = 0;
    while (received < kEvents && subscriber.next_notification(std::chrono::seconds(5))) ++received;
    const double s2 = seconds_since(t2);
    publisher.join();
    std::printf("events: %d of %d delivered in %.3f s = %.0f events/s\n", received, kEvents, s2,
                received / s2);

    server.stop();
    work.reset();
    io.stop();
    io_thread.join();
    std::filesystem::remove_all(dir);
    const bool ok = answered == kWindow * kWindows && received == kEvents;
    return ok ? 0 : 1;
}
