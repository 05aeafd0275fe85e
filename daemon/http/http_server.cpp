#include "daemon/http/http_server.hpp"

#include "daemon/http/http_connection.hpp"
#include "daemon/http/http_core.hpp"
#include "daemon/http/static_files.hpp"
#include "daemon/api/tcp_listener.hpp"

#include <spdlog/spdlog.h>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/strand.hpp>

namespace fibrecell::http {

namespace asio = boost::asio;
using asio::ip::tcp;

namespace {

constexpr std::size_t kMaxSessions = 256;

void accept_next(const std::shared_ptr<HttpCore>& core) {
    core->acceptor->async_accept(
        asio::make_strand(core->io), [core](const boost::system::error_code& ec, tcp::socket socket) {
            if (ec == asio::error::operation_aborted || !core->acceptor->is_open()) return;
            if (ec) {
                // Out of file descriptors or the like: wait a little instead of spinning.
                spdlog::warn("http.accept_failed: {}", ec.message());
                auto timer = std::make_shared<asio::steady_timer>(core->io, std::chrono::milliseconds(100));
                timer->async_wait([core, timer](const boost::system::error_code&) {
                    if (core->acceptor->is_open()) accept_next(core);
                });
                return;
            }
            core->counters.connections++;
            // As many HTTP connections as the API has clients, no more: a flood of them never
            // takes the descriptors the operator's control connections need.
            std::size_t limit = 0;
            bool say = false;  // at most once a second: a flood must not flood the log too
            {
                const std::lock_guard lock(core->mutex);
                limit = static_cast<std::size_t>(core->config.max_clients);
                if (core->counters.open.load() >= limit &&
                    Clock::now() - core->last_busy_warning > std::chrono::seconds(1)) {
                    core->last_busy_warning = Clock::now();
                    say = true;
                }
            }
            if (core->counters.open.load() >= limit) {
                // Full: the connection that has waited longest for its request goes (a client
                // that sends half a request and stops); with none waiting, the newcomer does.
                std::shared_ptr<HttpConnection> oldest;
                {
                    const std::lock_guard lock(core->mutex);
                    auto pick = core->waiting.end();
                    for (auto it = core->waiting.begin(); it != core->waiting.end(); ++it)
                        if (!it->second.second.expired() &&
                            (pick == core->waiting.end() || it->second.first < pick->second.first))
                            pick = it;
                    if (pick != core->waiting.end()) {
                        oldest = pick->second.second.lock();
                        core->waiting.erase(pick);
                    }
                }
                core->counters.refused_busy++;
                if (say)
                    spdlog::warn("http.connection_{}: {} HTTP connections open (api.max_clients); "
                                 "{} so far",
                                 oldest ? "closed_for_room" : "refused", limit,
                                 core->counters.refused_busy.load());
                if (oldest) {
                    oldest->close_for_room();
                    std::make_shared<HttpConnection>(core, std::move(socket))->start();
                } else {
                    boost::system::error_code ignored;
                    socket.close(ignored);
                }
            } else {
                std::make_shared<HttpConnection>(core, std::move(socket))->start();
            }
            accept_next(core);
        });
}

}  // namespace

HttpCore::HttpCore(asio::io_context& io_context, api::ApiConfig cfg, api::ApiServer& api_server)
    : io(io_context),
      api(api_server),
      web_root(default_web_root(cfg.http.web_root)),
      config(std::move(cfg)),
      sessions(config.http.session_lifetime, kMaxSessions),
      guard(config.http.login_failures_per_minute) {}

struct HttpServer::Impl {
    std::shared_ptr<HttpCore> core;
};

HttpServer::HttpServer(asio::io_context& io, api::ApiConfig config, api::ApiServer& api)
    : impl_(std::make_shared<Impl>()) {
    impl_->core = std::make_shared<HttpCore>(io, std::move(config), api);
}

HttpServer::~HttpServer() { stop(); }

void HttpServer::add_file_route(std::string prefix, FileResolver resolver) {
    impl_->core->file_routes.emplace_back(std::move(prefix), std::move(resolver));
}

void HttpServer::start() {
    HttpCore& core = *impl_->core;
    const api::ApiHttpConfig& c = core.config.http;
    const std::string where = "HTTP " + c.host + ":" + std::to_string(c.port);
    if (c.token.empty()) throw api::ApiStartError("cannot serve the dashboard on " + where + ": no token");
    if (!std::filesystem::is_regular_file(core.web_root / "index.html"))
        spdlog::warn("http.no_pages web_root={}: no index.html (set api.http.web_root)",
                     core.web_root.string());
    auto acceptor = api::listen_tcp(core.io, "HTTP", c.host, c.port);
    core.port = acceptor->local_endpoint().port();
    if (!acceptor->local_endpoint().address().is_loopback())
        spdlog::warn("http.exposed address={} port={}: the dashboard is reachable from other hosts "
                     "without TLS; put it behind an https proxy (docs/dashboard.md)",
                     c.host, core.port);
    core.acceptor = std::move(acceptor);
    spdlog::info("http.listening http://{}:{}/ web_root={}", c.host, core.port, core.web_root.string());
    accept_next(impl_->core);
}

void HttpServer::stop() {
    auto core = impl_->core;
    if (!core->acceptor) return;
    asio::post(core->io, [core] {
        boost::system::error_code ignored;
        core->acceptor->close(ignored);
    });
}

void HttpServer::update(const api::ApiConfig& config) {
    HttpCore& core = *impl_->core;
    const std::lock_guard lock(core.mutex);
    if (config.http.token != core.config.http.token) {
        core.sessions.close_all();
        spdlog::info("http.token_changed: every dashboard session ended");
    }
    core.guard.set_limit(config.http.login_failures_per_minute);
    const auto host = core.config.http.host;
    const auto port = core.config.http.port;
    const auto root = core.config.http.web_root;
    core.config = config;
    core.config.http.host = host;  // listeners and the web root need a restart
    core.config.http.port = port;
    core.config.http.web_root = root;
}

std::uint16_t HttpServer::port() const { return impl_->core->port; }

HttpStats HttpServer::stats() const {
    const HttpCounters& c = impl_->core->counters;
    return {.connections = c.connections.load(),
            .logins = c.logins.load(),
            .login_failures = c.login_failures.load(),
            .login_throttled = c.login_throttled.load(),
            .websockets = c.websockets.load(),
            .unauthorized = c.unauthorized.load(),
            .refused_busy = c.refused_busy.load(),
            .open = c.open.load()};
}

}  // namespace fibrecell::http
