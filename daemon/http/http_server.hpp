#pragma once
// The dashboard's HTTP listener (docs/dashboard.md): serves the pages under the web root, a login
// with the dashboard's token that sets an HTTP-only session cookie, and a WebSocket at /api/ws
// that speaks the socket API's JSON-RPC, served by the same ApiServer as every other client
// (ApiServer::open_bridge): one dispatcher, the same limits, the same errors.
//
//   HttpServer http(io, config.api, api);
//   http.add_file_route("/api/jobs/", [&](std::string_view id) { return plan_dir(id); });
//   http.start();   // throws api::ApiStartError with a one-line reason
//
// Threading: each connection runs on a strand of its own; the shared state is behind a mutex.
// start(), stop() and update() may be called from any thread; destroy after the io_context has
// stopped running or from one of its threads.

#include "daemon/api/api_config.hpp"
#include "daemon/api/api_server.hpp"
#include "daemon/http/file_route.hpp"

#include <boost/asio/io_context.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace fibrecell::http {

struct HttpStats {
    std::uint64_t connections = 0;     // HTTP connections accepted
    std::uint64_t logins = 0;          // right tokens
    std::uint64_t login_failures = 0;  // wrong tokens
    std::uint64_t login_throttled = 0; // refused unseen: too many wrong tokens from the address
    std::uint64_t websockets = 0;      // WebSocket upgrades accepted (each an API client)
    std::uint64_t unauthorized = 0;    // API requests without a valid session
    std::uint64_t refused_busy = 0;    // api.max_clients were open: the longest waiting, or this one, closed
    std::uint64_t open = 0;            // HTTP connections open now (a WebSocket is the API's)
};

class HttpServer {
  public:
    HttpServer(boost::asio::io_context& io, api::ApiConfig config, api::ApiServer& api);
    ~HttpServer();
    HttpServer(const HttpServer&) = delete;
    HttpServer& operator=(const HttpServer&) = delete;

    // Files behind the login under `prefix` ("/api/jobs/"). Before start().
    void add_file_route(std::string prefix, FileResolver resolver);

    void start();  // binds config.http.host:port; throws api::ApiStartError
    void stop();   // closes the listener; WebSockets end with the ApiServer's clients
    // A new token or login limit (SIGHUP): a changed token ends every session.
    void update(const api::ApiConfig& config);

    std::uint16_t port() const;  // the bound port
    HttpStats stats() const;

  private:
    struct Impl;
    std::shared_ptr<Impl> impl_;
};

}  // namespace fibrecell::http
