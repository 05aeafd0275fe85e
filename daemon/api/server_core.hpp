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

#include <atomic>
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

    // Listeners; set up by ApiServer::start() before any connection exists.
    std::unique_ptr<boost::asio::local::stream_protocol::acceptor> unix_acceptor;
    std::unique_ptr<boost::asio::ip::tcp::acceptor> tcp_acceptor;
    SocketFileId socket_id;  // the socket file we bound, removed on stop if still ours
    std::uint16_t tcp_port = 0;
};

}  // namespace fibrecell::api
