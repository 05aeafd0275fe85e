#include "drivers/sim/rws/rws_server.hpp"

#include <spdlog/spdlog.h>

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>

#include <map>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "config/thread_priority.hpp"
#include "drivers/abb/rws/digest.hpp"
#include "drivers/abb/rws/rws_json.hpp"
#include "drivers/sim/rws/rws_routes.hpp"

namespace fibrecell::drivers::sim::rws {

// Digest authentication and the JSON shape, shared with the client (drivers/abb/rws).
namespace json = abb::rws::json;
using abb::rws::DigestVerifier;
using abb::rws::random_hex;

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using tcp = asio::ip::tcp;

namespace {

using Request = http::request<http::string_body>;
using Response = http::response<http::string_body>;

constexpr std::string_view session_cookie = "-http-session-";

std::string_view sv(beast::string_view s) {
    return {s.data(), s.size()};
}

// The value of cookie `name` in a Cookie header ("a=1; b=2"), or empty.
std::string cookie_value(std::string_view header, std::string_view name) {
    while (!header.empty()) {
        const auto semi = header.find(';');
        std::string_view pair = header.substr(0, semi);
        header = semi == std::string_view::npos ? std::string_view() : header.substr(semi + 1);
        while (!pair.empty() && pair.front() == ' ') pair.remove_prefix(1);
        const auto eq = pair.find('=');
        if (eq != std::string_view::npos && pair.substr(0, eq) == name)
            return std::string(pair.substr(eq + 1));
    }
    return {};
}

class Connection;

// The server's state; RwsServer::Impl holds one.
struct Core {
    RwsServerConfig config;
    std::shared_ptr<RwsBackend> backend;
    DigestVerifier digest;
    asio::io_context io;
    tcp::acceptor acceptor{io};
    std::thread thread;
    std::uint16_t port = 0;

    mutable std::mutex mu;                             // everything below
    std::map<std::string, std::string> sessions;       // session id -> user
    std::map<std::string, std::string> nonce_session;  // nonce -> session id
    std::optional<std::string> master;                 // session holding RAPID mastership
    bool held_elsewhere = false;
    std::uint64_t cookie_counter = 0;
    RwsServerStats stats;
    std::vector<std::weak_ptr<Connection>> connections;

    Core(std::shared_ptr<RwsBackend> b, RwsServerConfig c)
        : config(std::move(c)),
          backend(std::move(b)),
          digest(DigestVerifier::Config{config.realm, config.user, config.password,
                                        config.nonce_lifetime}) {}

    void accept_next();
    Response handle(const Request& req);
    Response unauthorized(const Request& req, bool stale, const std::string& session);
    void close_all();
};

class Connection : public std::enable_shared_from_this<Connection> {
  public:
    Connection(tcp::socket socket, Core& server) : stream_(std::move(socket)), server_(server) {}

    void start() { read(); }

    void close() {
        beast::error_code ec;
        stream_.socket().shutdown(tcp::socket::shutdown_both, ec);
        stream_.close();
    }

  private:
    beast::tcp_stream stream_;
    Core& server_;
    beast::flat_buffer buffer_;
    std::optional<http::request_parser<http::string_body>> parser_;
    Response response_;

    void read() {
        parser_.emplace();
        parser_->body_limit(server_.config.max_body_bytes);
        stream_.expires_after(server_.config.idle_timeout);
        http::async_read(
            stream_, buffer_, *parser_,
            [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
    }

    void on_read(beast::error_code ec) {
        if (ec == http::error::body_limit) {
            response_ = Response(http::status::payload_too_large, 11);
            response_.set(http::field::content_type, "application/json");
            response_.body() = json::status_document(-4, "request body too large").dump();
            response_.keep_alive(false);
            response_.prepare_payload();
            write();
            return;
        }
        if (ec) {
            if (ec == beast::error::timeout) {
                std::lock_guard lock(server_.mu);
                ++server_.stats.idle_closes;
            }
            close();  // end of stream, idle timeout, reset, or the server stopping
            return;
        }
        const Request req = parser_->release();
        response_ = server_.handle(req);
        write();
    }

    void write() {
        stream_.expires_after(std::chrono::seconds(30));
        http::async_write(stream_, response_,
                          [self = shared_from_this()](beast::error_code ec, std::size_t) {
                              if (ec || !self->response_.keep_alive()) {
                                  self->close();
                                  return;
                              }
                              self->read();
                          });
    }
};

// Mastership as one session sees it.
class SessionGate : public MastershipGate {
  public:
    SessionGate(Core& s, std::string session) : s_(s), session_(std::move(session)) {}

    bool held_by_caller() const override {
        std::lock_guard lock(s_.mu);
        return !s_.held_elsewhere && s_.master == session_;
    }
    bool held_elsewhere() const override {
        std::lock_guard lock(s_.mu);
        return s_.held_elsewhere || (s_.master && *s_.master != session_);
    }
    bool request() override {
        std::lock_guard lock(s_.mu);
        if (s_.held_elsewhere || (s_.master && *s_.master != session_)) return false;
        s_.master = session_;
        return true;
    }
    void release() override {
        std::lock_guard lock(s_.mu);
        if (s_.master == session_) s_.master.reset();
    }

  private:
    Core& s_;
    std::string session_;
};

void Core::accept_next() {
    acceptor.async_accept([this](beast::error_code ec, tcp::socket socket) {
        if (!acceptor.is_open()) return;
        if (!ec) {
            auto c = std::make_shared<Connection>(std::move(socket), *this);
            {
                std::lock_guard lock(mu);
                std::erase_if(connections, [](const auto& w) { return w.expired(); });
                connections.push_back(c);
            }
            c->start();
        }
        accept_next();
    });
}

void Core::close_all() {
    beast::error_code ec;
    acceptor.close(ec);
    std::vector<std::weak_ptr<Connection>> all;
    {
        std::lock_guard lock(mu);
        all.swap(connections);
    }
    for (const auto& w : all)
        if (const auto c = w.lock()) c->close();
}

Response Core::unauthorized(const Request& req, bool stale, const std::string& session) {
    const DigestVerifier::Challenge c = digest.challenge(stale);
    {
        std::lock_guard lock(mu);
        if (stale && !session.empty()) nonce_session[c.nonce] = session;
        ++(stale ? stats.stale_challenges : stats.challenges);
    }
    Response res(http::status::unauthorized, req.version());
    res.set(http::field::www_authenticate, c.header);
    res.set(http::field::content_type, "application/json");
    res.body() =
        json::status_document(-1, stale ? "stale nonce" : "authentication required").dump();
    res.keep_alive(req.keep_alive());
    res.prepare_payload();
    return res;
}

Response Core::handle(const Request& req) {
    {
        std::lock_guard lock(mu);
        ++stats.requests;
    }
    const std::string method(req.method_string());
    const std::string target(req.target());
    const std::string_view authorization = sv(req[http::field::authorization]);
    const std::string cookie = cookie_value(sv(req[http::field::cookie]), session_cookie);

    std::string session;
    bool set_cookie = false;
    if (!authorization.empty()) {
        const DigestVerifier::Result v = digest.verify(authorization, method, target);
        if (v.verdict == DigestVerifier::Verdict::stale) {
            std::string old;
            {
                std::lock_guard lock(mu);
                const auto it = nonce_session.find(v.nonce);
                if (it != nonce_session.end()) old = it->second;
            }
            return unauthorized(req, true, old);
        }
        if (v.verdict != DigestVerifier::Verdict::ok) {
            if (v.verdict == DigestVerifier::Verdict::rejected) {
                spdlog::debug("rws_sim.auth_rejected {}", v.reason);
                std::lock_guard lock(mu);
                ++stats.rejected;
            }
            return unauthorized(req, false, {});
        }
        std::lock_guard lock(mu);
        ++stats.digest_logins;
        stats.max_nc = std::max(stats.max_nc, v.nc);
        auto it = nonce_session.find(v.nonce);
        if (it == nonce_session.end() || sessions.count(it->second) == 0) {
            const std::string id = random_hex(16);
            sessions[id] = config.user;
            ++stats.sessions_opened;
            it = nonce_session.insert_or_assign(v.nonce, id).first;
        }
        session = it->second;
        set_cookie = config.session_cookies && cookie != session;
    } else {
        bool valid = false;
        if (config.session_cookies && !cookie.empty()) {
            std::lock_guard lock(mu);
            valid = sessions.count(cookie) != 0;
        }
        if (!valid) return unauthorized(req, false, {});
        session = cookie;
    }

    if (target == "/logout") {
        std::lock_guard lock(mu);
        sessions.erase(session);
        std::erase_if(nonce_session, [&](const auto& kv) { return kv.second == session; });
        if (master == session) master.reset();
        Response res(http::status::no_content, req.version());
        res.keep_alive(req.keep_alive());
        res.prepare_payload();
        return res;
    }

    SessionGate gate(*this, session);
    std::string host(req[http::field::host]);
    if (host.empty()) host = config.address + ":" + std::to_string(port);
    RouteReply reply;
    try {
        reply = route({method, target, req.body(), host}, *backend, gate, config.task);
    } catch (const std::exception& e) {
        spdlog::error("rws_sim.backend_failed {} {}: {}", method, target, e.what());
        reply = {500, json::wire_text(json::status_document(-5, e.what()))};
    }

    Response res(static_cast<http::status>(reply.status), req.version());
    if (set_cookie) {
        std::uint64_t n = 0;
        {
            std::lock_guard lock(mu);
            n = ++cookie_counter;
        }
        res.insert(http::field::set_cookie,
                   std::string(session_cookie) + "=" + session + "; Path=/; HttpOnly");
        res.insert(http::field::set_cookie, "ABBCX=" + std::to_string(n) + "; Path=/; HttpOnly");
    }
    if (reply.status != 204) {
        res.set(http::field::content_type, reply.content_type);
        res.body() = std::move(reply.body);
    }
    res.keep_alive(req.keep_alive());
    res.prepare_payload();
    return res;
}

}  // namespace

struct RwsServer::Impl {
    Core core;
    Impl(std::shared_ptr<RwsBackend> b, RwsServerConfig c) : core(std::move(b), std::move(c)) {}
};

RwsServer::RwsServer(std::shared_ptr<RwsBackend> backend, RwsServerConfig config)
    : impl_(std::make_unique<Impl>(std::move(backend), std::move(config))) {
    Core& s = impl_->core;
    const std::string where = s.config.address + ":" + std::to_string(s.config.port);
    try {
        const tcp::endpoint ep(asio::ip::make_address(s.config.address), s.config.port);
        s.acceptor.open(ep.protocol());
        s.acceptor.set_option(asio::socket_base::reuse_address(true));
        s.acceptor.bind(ep);
        s.acceptor.listen();
        s.port = s.acceptor.local_endpoint().port();
    } catch (const boost::system::system_error& e) {
        throw std::runtime_error("RWS simulator cannot listen on " + where + ": " +
                                 e.code().message());
    }
    s.accept_next();
    s.thread = std::thread([&s] {
        config::name_this_thread("sim.rws");
        try {
            s.io.run();
        } catch (const std::exception& e) {
            spdlog::error("rws_sim.io_failed {}", e.what());
        }
    });
    spdlog::debug("rws_sim.listening {}:{}", s.config.address, s.port);
}

RwsServer::~RwsServer() {
    stop();
}

std::uint16_t RwsServer::port() const {
    return impl_->core.port;
}
const std::string& RwsServer::address() const {
    return impl_->core.config.address;
}

void RwsServer::stop() {
    Core& s = impl_->core;
    if (!s.thread.joinable()) return;
    asio::post(s.io, [&s] { s.close_all(); });
    s.thread.join();
}

void RwsServer::set_mastership_held_elsewhere(bool held) {
    std::lock_guard lock(impl_->core.mu);
    impl_->core.held_elsewhere = held;
}

bool RwsServer::mastership_held() const {
    std::lock_guard lock(impl_->core.mu);
    return impl_->core.master.has_value();
}

void RwsServer::expire_nonces() {
    impl_->core.digest.expire_nonces();
}

void RwsServer::end_sessions() {
    std::lock_guard lock(impl_->core.mu);
    impl_->core.sessions.clear();
    impl_->core.nonce_session.clear();
    impl_->core.master.reset();
}

RwsServerStats RwsServer::stats() const {
    std::lock_guard lock(impl_->core.mu);
    return impl_->core.stats;
}

}  // namespace fibrecell::drivers::sim::rws
