#pragma once
// The service side of the socket API (docs/socket-api.md): newline-delimited JSON-RPC 2.0 over a
// Unix socket and, when configured, TCP with a token. Transport and protocol only: the job logic
// registers its methods here and publishes its events through publish().
//
//   boost::asio::io_context io;
//   ApiServer api(io, config);
//   api.add_method("job.list", [&](const json& params, const CallContext&) { ... });
//   api.start();                       // binds; throws ApiStartError with a one-line reason
//   std::thread io_thread([&] { io.run(); });
//   api.publish({.topic = job_id, .method = notify::job_state, .params = {...}});
//
// Threading: the server does all its work on one strand of the caller's io_context (which may
// run on several threads). Register methods before start(). publish(), stop(), stats() and
// Responder are safe from any thread. Sync handlers run on the strand: keep them short and hand
// long work to workers through an async handler. Destroy the server from an io thread or once
// the io_context no longer runs, and before the io_context.

#include "daemon/api/api_config.hpp"
#include "daemon/api/api_event.hpp"
#include "daemon/api/method_registry.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/local/stream_protocol.hpp>

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace fibrecell::api {

class ApiStartError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

struct ApiServerStats {
    std::uint64_t clients = 0;                  // connected now
    std::uint64_t connections = 0;              // accepted since start
    std::uint64_t requests = 0;                 // request objects dispatched (batch entries count)
    std::uint64_t errors = 0;                   // error responses sent
    std::uint64_t notifications_sent = 0;       // notification lines queued to clients
    std::uint64_t notifications_coalesced = 0;  // latest-only events replaced before sending
    std::uint64_t dropped_slow = 0;             // clients disconnected for an overfull queue
    std::uint64_t refused_full = 0;             // connections refused (max + reserved full, all busy)
    std::uint64_t evicted = 0;                  // closed to make room for a newer connection
    std::uint64_t control_only = 0;             // admitted into the reserved control capacity
    std::uint64_t closed_idle = 0;              // closed after api.idle_timeout_s
    std::uint64_t oversized = 0;                // request lines above api.max_request_bytes
    std::uint64_t auth_failures = 0;            // wrong token or no server.auth in time
};

class ApiServer {
  public:
    ApiServer(boost::asio::io_context& io, ApiConfig config);
    ~ApiServer();
    ApiServer(const ApiServer&) = delete;
    ApiServer& operator=(const ApiServer&) = delete;

    // `owner`: the service's component that answers it (daemon/component/endpoints.hpp).
    void add_method(std::string name, SyncHandler handler, std::string owner = {});
    void add_async_method(std::string name, AsyncHandler handler, std::string owner = {});
    // A method the operator must always reach (status, pause, abort, estop): callable from the
    // reserved capacity beyond api.max_clients. Register it first.
    void add_control_method(const std::string& name);
    // An event (notify.*) that `owner` publishes, for the registry's list.
    void add_event(std::string name, std::string owner);
    // What is registered: every method (built-ins too) and event with its owner.
    std::vector<Registration> methods() const;
    std::vector<Registration> events() const;

    // Binds the Unix socket (a stale file from a dead process is replaced; a live one is
    // "another fibrecelld is listening on <path>") with its mode and group, and TCP when enabled;
    // then accepts on the io_context. Throws ApiStartError.
    void start();
    // Closes the listeners and every connection and removes the socket file (if still ours).
    // Idempotent; asynchronous when called off the strand.
    void stop();

    // Sends an event to every client subscribed to its topic (or to "*"). Thread-safe; events
    // published from one thread reach each client in that order.
    void publish(ApiEvent event);

    // Applies the settings that need no new listener (token, limits, progress rate); a changed
    // socket path/mode/group or TCP address takes a restart. Thread-safe.
    void update_limits(const ApiConfig& config);

    // A connection another listener accepted and authenticated (the dashboard's WebSocket,
    // daemon/http): returns our end of a local socket pair whose other end is served like any
    // client (same methods, limits and events), newline-delimited. `peer` names it in logs,
    // `user` in records (CallContext::user).
    // Thread-safe; after stop() the returned socket reads EOF at once.
    boost::asio::local::stream_protocol::socket open_bridge(std::string peer, std::string user);

    std::uint16_t tcp_port() const;  // the bound TCP port (0 when TCP is off)
    const std::string& socket_path() const;
    ApiServerStats stats() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace fibrecell::api
