#pragma once
// Internal: the state every connection of one ApiServer shares. Touched only on `strand`, except
// the counters (atomics, read by stats()).

#include "daemon/api/api_config.hpp"
#include "daemon/api/api_server.hpp"
#include "daemon/api/method_registry.hpp"

#include "daemon/api/socket_file.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/local/stream_protocol.hpp>
#include <boost/asio/strand.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>

namespace fibrecell::api {

class ClientSession;

using Strand = boost::asio::strand<boost::asio::io_context::executor_type>;

struct ServerCounters {
    std::atomic<std::uint64_t> clients{0};
    std::atomic<std::uint64_t> connections{0};
    std::atomic<std::uint64_t> requests{0};
    std::atomic<std::uint64_t> errors{0};
    std::atomic<std::uint64_t> notifications_sent{0};
    std::atomic<std::uint64_t> notifications_coalesced{0};
    std::atomic<std::uint64_t> dropped_slow{0};
    std::atomic<std::uint64_t> refused_full{0};
    std::atomic<std::uint64_t> evicted{0};  // closed to make room for a newer connection
    std::atomic<std::uint64_t> control_only{0};
    std::atomic<std::uint64_t> closed_idle{0};
    std::atomic<std::uint64_t> oversized{0};
    std::atomic<std::uint64_t> auth_failures{0};
};

struct ServerCore {
    ServerCore(boost::asio::io_context& io_context, ApiConfig cfg)
        : io(io_context), strand(boost::asio::make_strand(io_context)), config(std::move(cfg)) {}

    boost::asio::io_context& io;
    Strand strand;
    ApiConfig config;
    MethodRegistry methods;
    std::map<std::uint64_t, std::weak_ptr<ClientSession>> sessions;
    std::uint64_t next_client = 1;
    bool stopped = false;
    ServerCounters counters;
    std::chrono::steady_clock::time_point evicted_logged_at{};  // api.client_closed_for_room
    // Token checks left in this second (api.tcp.auth_attempts_per_s), refilled continuously.
    double auth_attempts_left = -1;  // < 0: full, not started
    std::chrono::steady_clock::time_point auth_attempts_at{};

    // Takes one token check from the budget; false when it is spent.
    bool take_auth_attempt() {
        const double rate = config.tcp.auth_attempts_per_s;
        const auto now = std::chrono::steady_clock::now();
        if (auth_attempts_left < 0) auth_attempts_left = rate;
        auth_attempts_left = std::min(
            rate, auth_attempts_left + rate * std::chrono::duration<double>(now - auth_attempts_at).count());
        auth_attempts_at = now;
        if (auth_attempts_left < 1) return false;
        auth_attempts_left -= 1;
        return true;
    }
    std::uint64_t evicted_unlogged = 0;

    // Listeners; set up by ApiServer::start() before any connection exists.
    std::unique_ptr<boost::asio::local::stream_protocol::acceptor> unix_acceptor;
    std::unique_ptr<boost::asio::ip::tcp::acceptor> tcp_acceptor;
    SocketFileId socket_id;  // the socket file we bound, removed on stop if still ours
    std::uint16_t tcp_port = 0;
};

}  // namespace fibrecell::api
