#include "daemon/api/api_server.hpp"

#include "daemon/api/client_session.hpp"
#include "daemon/api/server_core.hpp"
#include "daemon/api/socket_file.hpp"
#include "daemon/api/tcp_listener.hpp"

#include <spdlog/spdlog.h>
#include <boost/asio/bind_executor.hpp>
#include <boost/asio/dispatch.hpp>
#include <boost/asio/local/connect_pair.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>

#include <pwd.h>
#include <sys/socket.h>

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

namespace fibrecell::api {

namespace asio = boost::asio;
using local_stream = asio::local::stream_protocol;
using asio::ip::tcp;

namespace {

// The connecting process, for logs, and its user's name, for records.
std::pair<std::string, std::string> unix_peer(int fd) {
    ucred cred{};
    socklen_t len = sizeof cred;
    if (::getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &cred, &len) != 0) return {"unix", "unix"};
    std::string user = "uid " + std::to_string(cred.uid);
    passwd pw{};
    passwd* found = nullptr;
    std::array<char, 4096> buf{};
    if (::getpwuid_r(cred.uid, &pw, buf.data(), buf.size(), &found) == 0 && found)
        user = found->pw_name;
    return {"unix uid=" + std::to_string(cred.uid) + " pid=" + std::to_string(cred.pid), user};
}

std::vector<std::shared_ptr<ClientSession>> live_sessions(const ServerCore& core) {
    std::vector<std::shared_ptr<ClientSession>> out;
    for (const auto& [id, weak] : core.sessions)
        if (auto s = weak.lock()) out.push_back(std::move(s));
    return out;
}

// The connections not on their way out (a closing one drains for at most 2 s).
std::vector<std::shared_ptr<ClientSession>> open_sessions(const ServerCore& core) {
    auto open = live_sessions(core);
    std::erase_if(open, [](const auto& s) { return s->closing(); });
    return open;
}

// Whom to close to make room: a connection that has not authenticated first, then the one idle
// longest; never one with a call in progress, nor the newcomer. Null when there is none.
std::shared_ptr<ClientSession> longest_idle(const std::vector<std::shared_ptr<ClientSession>>& open,
                                            std::uint64_t newcomer, bool unauthenticated_only) {
    std::shared_ptr<ClientSession> pick;
    const auto before = [](const ClientSession& a, const ClientSession& b) {
        if (a.unauthenticated_tcp() != b.unauthenticated_tcp()) return a.unauthenticated_tcp();
        return a.last_active() < b.last_active();
    };
    for (const auto& s : open) {
        if (s->id() == newcomer || s->busy()) continue;
        if (unauthenticated_only && !s->unauthenticated_tcp()) continue;
        if (!pick || before(*s, *pick)) pick = s;
    }
    return pick;
}

// Logged once a second at most: a flood of connections must not become a flood of log lines.
void make_room(ServerCore& core, const std::shared_ptr<ClientSession>& victim, const char* reason,
               const std::string& message) {
    core.counters.evicted++;
    ++core.evicted_unlogged;
    const auto now = std::chrono::steady_clock::now();
    if (now - core.evicted_logged_at >= std::chrono::seconds(1)) {
        spdlog::warn("api.client_closed_for_room client={} peer={} reason={} ({} closed so since "
                     "the last such line)",
                     victim->id(), victim->peer(), reason, core.evicted_unlogged);
        core.evicted_logged_at = now;
        core.evicted_unlogged = 0;
    }
    victim->refuse(error_response(nullptr, errc::unavailable, message));
}

// A new connection is always let in while anyone else can make room for it: a client allowed on
// the socket (its file permissions, the token on TCP) gets its control call answered whatever the
// other connections do (docs/socket-api.md, "Connections").
void admit(const std::shared_ptr<ServerCore>& core, ClientSession::Socket socket,
           Transport transport, std::string peer, std::string user) {
    const std::uint64_t id = core->next_client++;
    core->counters.connections++;
    core->counters.clients++;
    auto session =
        std::make_shared<ClientSession>(core, std::move(socket), id, transport, std::move(peer),
                                        std::move(user));
    core->sessions[id] = session;
    auto open = open_sessions(*core);
    if (session->unauthenticated_tcp()) {
        const auto limit = static_cast<std::size_t>(core->config.tcp.max_unauthenticated);
        const auto waiting = std::count_if(open.begin(), open.end(),
                                           [](const auto& s) { return s->unauthenticated_tcp(); });
        if (static_cast<std::size_t>(waiting) > limit) {
            if (auto oldest = longest_idle(open, id, true)) {
                make_room(*core, oldest, "max_unauthenticated",
                          "unavailable: closed for a newer connection: at most " +
                              std::to_string(limit) +
                              " connections may wait for server.auth (api.tcp.max_unauthenticated)");
                open = open_sessions(*core);
            }
        }
    }
    const auto max = static_cast<std::size_t>(core->config.max_clients);
    const auto reserved = static_cast<std::size_t>(core->config.reserved_control_clients);
    if (open.size() > max + reserved) {
        auto victim = longest_idle(open, id, false);
        if (!victim) {  // every other connection has a call in progress
            core->counters.refused_full++;
            spdlog::warn("api.client_refused client={} peer={} reason=max_clients limit={}+{}", id,
                         session->peer(), max, reserved);
            session->refuse(error_response(nullptr, errc::unavailable,
                                           "unavailable: fibrecelld serves at most " +
                                               std::to_string(max) +
                                               " clients at once (api.max_clients), all busy"));
            return;
        }
        make_room(*core, victim, "max_clients",
                  "unavailable: closed for a newer connection: fibrecelld serves at most " +
                      std::to_string(max + reserved) +
                      " clients at once (api.max_clients + api.reserved_control_clients); the one "
                      "idle longest goes first");
        open = open_sessions(*core);
    }
    if (open.size() > max) {
        core->counters.control_only++;
        session->restrict_to_control();
        spdlog::debug("api.client_control_only client={} peer={}: {} clients connected, this one "
                     "may only call the control methods",
                     id, session->peer(), max);
    }
    spdlog::debug("api.client_connected client={} peer={}", id, session->peer());  // a flood is not logged
    session->start();
}

// After an accept error (out of file descriptors, ...) wait a little instead of spinning.
template <class Retry>
void retry_later(const std::shared_ptr<ServerCore>& core, Retry retry) {
    auto timer = std::make_shared<asio::steady_timer>(core->strand, std::chrono::milliseconds(100));
    timer->async_wait([timer, retry](const boost::system::error_code&) { retry(); });
}

void accept_unix(const std::shared_ptr<ServerCore>& core) {
    core->unix_acceptor->async_accept(asio::bind_executor(
        core->strand, [core](const boost::system::error_code& ec, local_stream::socket socket) {
            if (core->stopped || ec == asio::error::operation_aborted) return;
            if (ec) {
                spdlog::warn("api.accept_failed transport=unix: {}", ec.message());
                retry_later(core, [core] {
                    if (!core->stopped) accept_unix(core);
                });
                return;
            }
            auto [peer, user] = unix_peer(socket.native_handle());
            ClientSession::Socket generic(core->io, asio::generic::stream_protocol(local_stream()),
                                          socket.release());
            admit(core, std::move(generic), Transport::unix_socket, std::move(peer), std::move(user));
            accept_unix(core);
        }));
}

void accept_tcp(const std::shared_ptr<ServerCore>& core) {
    core->tcp_acceptor->async_accept(asio::bind_executor(
        core->strand, [core](const boost::system::error_code& ec, tcp::socket socket) {
            if (core->stopped || ec == asio::error::operation_aborted) return;
            if (ec) {
                spdlog::warn("api.accept_failed transport=tcp: {}", ec.message());
                retry_later(core, [core] {
                    if (!core->stopped) accept_tcp(core);
                });
                return;
            }
            boost::system::error_code ignored;
            socket.set_option(tcp::no_delay(true), ignored);
            const auto remote = socket.remote_endpoint(ignored);
            std::string peer =
                "tcp " + remote.address().to_string() + ":" + std::to_string(remote.port());
            const auto protocol = asio::generic::stream_protocol(remote.protocol());
            ClientSession::Socket generic(core->io, protocol, socket.release());
            admit(core, std::move(generic), Transport::tcp, std::move(peer),
                  "tcp " + remote.address().to_string());
            accept_tcp(core);
        }));
}

// Closes listeners and removes the socket file; `graceful` lets queued answers go out first.
void stop_core(const std::shared_ptr<ServerCore>& core, bool graceful) {
    if (core->stopped) return;
    core->stopped = true;
    boost::system::error_code ignored;
    if (core->unix_acceptor) core->unix_acceptor->close(ignored);
    if (core->tcp_acceptor) core->tcp_acceptor->close(ignored);
    remove_socket_file_if_ours(core->config.socket_path, core->socket_id);
    core->socket_id = {};
    for (const auto& s : live_sessions(*core)) {
        if (graceful)
            s->shutdown();
        else
            s->close("server stopping");
    }
    spdlog::info("api.stopped");
}

void bind_unix(ServerCore& core) {
    const ApiConfig& c = core.config;
    prepare_socket_path(c.socket_path);
    auto acceptor = std::make_unique<local_stream::acceptor>(core.io);
    boost::system::error_code ec;
    acceptor->open(local_stream(), ec);
    if (!ec) acceptor->bind(local_stream::endpoint(c.socket_path), ec);
    if (ec) throw ApiStartError("cannot create socket " + c.socket_path + ": " + ec.message());
    try {
        // Mode and group before listen(): nobody connects through a wider mode meanwhile.
        apply_socket_permissions(c.socket_path, c.socket_mode, c.socket_group);
    } catch (...) {
        acceptor->close(ec);
        ::unlink(c.socket_path.c_str());
        throw;
    }
    core.socket_id = identify_socket_file(c.socket_path);
    acceptor->listen(asio::socket_base::max_listen_connections, ec);
    if (ec) {
        remove_socket_file_if_ours(c.socket_path, core.socket_id);
        throw ApiStartError("cannot listen on " + c.socket_path + ": " + ec.message());
    }
    core.unix_acceptor = std::move(acceptor);
}

void bind_tcp(ServerCore& core) {
    const ApiTcpConfig& c = core.config.tcp;
    const std::string where = "TCP " + c.host + ":" + std::to_string(c.port);
    if (c.token.empty())
        throw ApiStartError("cannot listen on " + where + ": api.tcp needs a token");
    auto acceptor = listen_tcp(core.io, "TCP", c.host, c.port);
    core.tcp_port = acceptor->local_endpoint().port();
    if (!acceptor->local_endpoint().address().is_loopback())
        spdlog::warn("api.tcp_exposed address={} port={}: reachable from other hosts (token only)",
                     c.host, core.tcp_port);
    core.tcp_acceptor = std::move(acceptor);
}

}  // namespace

struct ApiServer::Impl {
    std::shared_ptr<ServerCore> core;
    bool started = false;
};

ApiServer::ApiServer(boost::asio::io_context& io, ApiConfig config)
    : impl_(std::make_unique<Impl>()) {
    impl_->core = std::make_shared<ServerCore>(io, std::move(config));
}

ApiServer::~ApiServer() {
    if (impl_->started) stop_core(impl_->core, false);
}

void ApiServer::add_method(std::string name, SyncHandler handler, std::string owner) {
    impl_->core->methods.add(std::move(name), std::move(handler), std::move(owner));
}

void ApiServer::add_async_method(std::string name, AsyncHandler handler, std::string owner) {
    impl_->core->methods.add_async(std::move(name), std::move(handler), std::move(owner));
}

void ApiServer::add_control_method(const std::string& name) {
    impl_->core->methods.mark_control(name);
}

void ApiServer::add_event(std::string name, std::string owner) {
    impl_->core->methods.add_event(std::move(name), std::move(owner));
}

std::vector<Registration> ApiServer::methods() const { return impl_->core->methods.methods(); }

std::vector<Registration> ApiServer::events() const { return impl_->core->methods.events(); }

void ApiServer::start() {
    if (impl_->started) throw ApiStartError("the API server is already started");
    const auto& core = impl_->core;
    if (core->config.socket_path.empty() && !core->config.tcp.enabled)
        throw ApiStartError("the API has neither a socket path nor TCP enabled");
    if (!core->config.socket_path.empty()) bind_unix(*core);
    try {
        if (core->config.tcp.enabled) bind_tcp(*core);
    } catch (...) {
        boost::system::error_code ignored;
        if (core->unix_acceptor) core->unix_acceptor->close(ignored);
        remove_socket_file_if_ours(core->config.socket_path, core->socket_id);
        throw;
    }
    impl_->started = true;
    if (core->unix_acceptor)
        spdlog::info("api.listening socket={} mode={:04o} group={}", core->config.socket_path,
                     core->config.socket_mode,
                     core->config.socket_group.empty() ? "-" : core->config.socket_group);
    if (core->tcp_acceptor)
        spdlog::info("api.listening tcp={}:{}", core->config.tcp.host, core->tcp_port);
    asio::dispatch(core->strand, [core] {
        if (core->stopped) return;
        if (core->unix_acceptor) accept_unix(core);
        if (core->tcp_acceptor) accept_tcp(core);
    });
}

void ApiServer::stop() {
    if (!impl_->started) return;
    asio::dispatch(impl_->core->strand, [core = impl_->core] { stop_core(core, true); });
}

void ApiServer::publish(ApiEvent event) {
    auto line = std::make_shared<const std::string>(
        to_line(notification_message(event.method, std::move(event.params))));
    // Posted, never run inline: events from one thread keep their order.
    asio::post(impl_->core->strand, [core = impl_->core, topic = std::move(event.topic),
                                     method = std::move(event.method), delivery = event.delivery,
                                     line = std::move(line)] {
        if (core->stopped) return;
        for (const auto& s : live_sessions(*core)) s->deliver(topic, method, delivery, line);
    });
}

void ApiServer::update_limits(const ApiConfig& config) {
    asio::post(impl_->core->strand, [core = impl_->core, config] {
        core->config.tcp.token = config.tcp.token;
        core->config.tcp.auth_timeout = config.tcp.auth_timeout;
        core->config.max_request_bytes = config.max_request_bytes;
        core->config.max_clients = config.max_clients;
        core->config.reserved_control_clients = config.reserved_control_clients;
        core->config.idle_timeout = config.idle_timeout;
        core->config.control_idle_timeout = config.control_idle_timeout;
        core->config.max_client_queue_bytes = config.max_client_queue_bytes;
        core->config.max_batch_calls = config.max_batch_calls;
        core->config.progress_rate_hz = config.progress_rate_hz;
        const auto interval =
            std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / config.progress_rate_hz));
        for (const auto& s : live_sessions(*core)) s->set_progress_interval(interval);
        spdlog::info("api.limits_updated max_request_bytes={} max_clients={} progress_rate_hz={}",
                     config.max_request_bytes, config.max_clients, config.progress_rate_hz);
    });
}

local_stream::socket ApiServer::open_bridge(std::string peer, std::string user) {
    const auto& core = impl_->core;
    local_stream::socket ours(core->io);
    local_stream::socket theirs(core->io);
    asio::local::connect_pair(ours, theirs);
    asio::post(core->strand, [core, peer = std::move(peer), user = std::move(user),
                              sock = std::make_shared<local_stream::socket>(std::move(theirs))] {
        if (core->stopped) return;  // closing `sock` here: the caller's end reads EOF
        ClientSession::Socket generic(core->io, asio::generic::stream_protocol(local_stream()),
                                      sock->release());
        admit(core, std::move(generic), Transport::websocket, peer, user);
    });
    return ours;
}

std::uint16_t ApiServer::tcp_port() const {
    return impl_->core->tcp_port;
}

const std::string& ApiServer::socket_path() const {
    return impl_->core->config.socket_path;
}

ApiServerStats ApiServer::stats() const {
    const ServerCounters& c = impl_->core->counters;
    ApiServerStats s;
    s.clients = c.clients.load();
    s.connections = c.connections.load();
    s.requests = c.requests.load();
    s.errors = c.errors.load();
    s.notifications_sent = c.notifications_sent.load();
    s.notifications_coalesced = c.notifications_coalesced.load();
    s.dropped_slow = c.dropped_slow.load();
    s.refused_full = c.refused_full.load();
    s.evicted = c.evicted.load();
    s.control_only = c.control_only.load();
    s.closed_idle = c.closed_idle.load();
    s.oversized = c.oversized.load();
    s.auth_failures = c.auth_failures.load();
    return s;
}

}  // namespace fibrecell::api
