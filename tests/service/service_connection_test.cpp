// Control is always reachable (docs/socket-api.md, "Connections"): whatever other connections do,
// a client allowed on the socket gets its E-stop answered. 100 clients connect and hold their
// connection idle, and connect again the moment it is closed (70 on the Unix socket, 30 over TCP
// that never send the token); meanwhile the operator connects and calls cell.estop 100 times.
#include "service_fixture.hpp"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <thread>
#include <vector>

using namespace fibrecell;
using namespace fibrecell::test;

namespace {

// One hostile client: connects, sends nothing, waits until the server closes the connection,
// and connects again at once, until `stop`. Counts its connections.
void hold_and_reconnect(const fs::path& socket_path, int tcp_port, const std::atomic<bool>& stop,
                        std::atomic<long>& connections) {
    while (!stop.load()) {
        const int fd = ::socket(tcp_port ? AF_INET : AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
        if (fd < 0) continue;
        int rc = -1;
        if (tcp_port) {
            sockaddr_in a{};
            a.sin_family = AF_INET;
            a.sin_port = htons(static_cast<std::uint16_t>(tcp_port));
            a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
            rc = ::connect(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a);
        } else {
            sockaddr_un a{};
            a.sun_family = AF_UNIX;
            std::strncpy(a.sun_path, socket_path.c_str(), sizeof a.sun_path - 1);
            rc = ::connect(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a);
        }
        if (rc == 0) {
            ++connections;
            // Held until the server closes it (or the test ends: a read time-out lets it see stop).
            timeval tv{0, 200'000};
            ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
            char buf[512];
            while (!stop.load()) {
                const ssize_t n = ::read(fd, buf, sizeof buf);
                if (n == 0 || (n < 0 && errno != EAGAIN && errno != EINTR)) break;
            }
        }
        ::close(fd);
    }
}

}  // namespace

TEST_F(ServiceTest, ReconnectingIdleClientsNeverKeepTheEstopFromTheOperator) {
    start_service(write_config());
    const int tcp_port = [&] {
        auto c = client();
        return c.call("server.info").value("tcp_port", 0);
    }();
    ASSERT_GT(tcp_port, 0);

    std::atomic<bool> stop{false};
    std::atomic<long> connections{0};
    std::vector<std::thread> flood;
    for (int i = 0; i < 100; ++i)
        flood.emplace_back(hold_and_reconnect, socket(), i < 70 ? 0 : tcp_port, std::cref(stop),
                           std::ref(connections));
    // The flood is on: more connections than the service holds have been made.
    ASSERT_TRUE(eventually([&] { return connections.load() > 200; }, 60s)) << connections.load();

    std::vector<double> ms;
    int answered = 0;
    std::string failure;
    for (int i = 0; i < 100; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        try {
            auto c = client();
            if (c.call("cell.estop", json::object(), 10s).is_object()) ++answered;
        } catch (const std::exception& e) {
            if (failure.empty()) failure = e.what();
        }
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    const long flooded = connections.load();
    stop = true;
    for (auto& t : flood) t.join();

    std::sort(ms.begin(), ms.end());
    const double p50 = ms[ms.size() / 2], p99 = ms[ms.size() * 99 / 100], worst = ms.back();
    std::printf("100 E-stops among 100 reconnecting idle clients (%ld connections): %d answered; "
                "connect + call p50 %.1f ms, p99 %.1f ms, max %.1f ms\n",
                flooded, answered, p50, p99, worst);
    EXPECT_EQ(answered, 100) << "first failure: " << failure;
    // A generous bound (ASan, a loaded machine): the figures are printed. Before, none was
    // answered for as long as the flood ran.
    EXPECT_LT(p99, 2000.0);
    // And the service is whole.
    auto c = client();
    EXPECT_TRUE(c.call("cell.status").is_object());
}
