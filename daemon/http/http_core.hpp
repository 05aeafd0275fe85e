#pragma once
// Internal: what every connection of one HttpServer shares. The config, sessions and login guard
// are behind `mutex`; the counters are atomics.

#include "daemon/api/api_config.hpp"
#include "daemon/api/api_server.hpp"
#include "daemon/http/http_server.hpp"
#include "daemon/http/login_sessions.hpp"

#include <boost/asio/ip/tcp.hpp>

#include <atomic>
#include <map>
#include <memory>
#include <filesystem>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace fibrecell::http {

struct HttpCounters {
    std::atomic<std::uint64_t> connections{0};
    std::atomic<std::uint64_t> logins{0};
    std::atomic<std::uint64_t> login_failures{0};
    std::atomic<std::uint64_t> login_throttled{0};
    std::atomic<std::uint64_t> websockets{0};
    std::atomic<std::uint64_t> unauthorized{0};
    std::atomic<std::uint64_t> refused_busy{0};
    std::atomic<std::uint64_t> open{0};  // HTTP connections now (not yet WebSockets)
};

class HttpConnection;

struct HttpCore {
    HttpCore(boost::asio::io_context& io_context, api::ApiConfig cfg, api::ApiServer& api_server);

    boost::asio::io_context& io;
    api::ApiServer& api;
    const std::filesystem::path web_root;
    std::vector<std::pair<std::string, FileResolver>> file_routes;  // set before start()
    HttpCounters counters;
    std::unique_ptr<boost::asio::ip::tcp::acceptor> acceptor;
    std::uint16_t port = 0;

    std::mutex mutex;
    api::ApiConfig config;  // guarded
    SessionTable sessions;  // guarded
    LoginGuard guard;       // guarded
    Clock::time_point last_busy_warning;  // guarded
    // Connections waiting for (the rest of) a request, by when they began to wait: when the
    // listener is full, the one waiting longest makes room for the newcomer (half-sent requests
    // never keep the dashboard from the operator).
    std::map<std::uint64_t, std::pair<Clock::time_point, std::weak_ptr<HttpConnection>>> waiting;  // guarded
    std::uint64_t next_connection = 1;  // guarded
};

}  // namespace fibrecell::http
