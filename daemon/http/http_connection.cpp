#include "daemon/http/http_connection.hpp"

#include "daemon/http/http_routes.hpp"
#include "daemon/http/static_files.hpp"
#include "daemon/http/websocket_bridge.hpp"

#include <spdlog/spdlog.h>
#include <boost/asio/dispatch.hpp>
#include <boost/beast/core/bind_handler.hpp>
#include <boost/beast/http/empty_body.hpp>
#include <boost/beast/http/file_body.hpp>
#include <boost/beast/http/read.hpp>
#include <boost/beast/http/write.hpp>
#include <boost/beast/websocket/rfc6455.hpp>

namespace fibrecell::http {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace bhttp = beast::http;
namespace websocket = beast::websocket;

namespace {

constexpr auto kRequestTimeout = std::chrono::seconds(30);
constexpr std::size_t kMaxHeaderBytes = 16 * 1024;
constexpr std::size_t kWebSocketSlack = 1 << 20;  // over the API's queue limit: its longest line

// The pages' Content-Security-Policy: scripts, styles and connections from this origin only.
constexpr const char* kPagePolicy =
    "default-src 'self'; img-src 'self' data: blob:; style-src 'self' 'unsafe-inline'; "
    "object-src 'none'; frame-ancestors 'none'; base-uri 'none'";

using FileResponse = bhttp::response<bhttp::file_body>;

std::optional<FileResponse> file_response(const Request& req, const std::filesystem::path& path,
                                          const std::string& content_type) {
    bhttp::file_body::value_type body;
    beast::error_code ec;
    body.open(path.c_str(), beast::file_mode::scan, ec);
    if (ec) return std::nullopt;
    const auto size = body.size();
    FileResponse res{std::piecewise_construct, std::make_tuple(std::move(body)),
                     std::make_tuple(bhttp::status::ok, req.version())};
    add_common_headers(res, req);
    res.set(bhttp::field::content_type, content_type);
    res.set(bhttp::field::cache_control, "no-cache");
    if (content_type.rfind("text/html", 0) == 0)
        res.set("Content-Security-Policy", kPagePolicy);
    res.content_length(size);
    return res;
}

std::string target_path(const Request& req) {
    const std::string_view t(req.target().data(), req.target().size());
    return std::string(t.substr(0, t.find_first_of("?#")));
}

}  // namespace

HttpConnection::HttpConnection(std::shared_ptr<HttpCore> core, asio::ip::tcp::socket socket)
    : core_(std::move(core)), stream_(std::move(socket)) {
    boost::system::error_code ec;
    const auto remote = stream_.socket().remote_endpoint(ec);
    address_ = ec ? "unknown" : remote.address().to_string();
    peer_ = ec ? "unknown" : address_ + ":" + std::to_string(remote.port());
    core_->counters.open++;
    const std::lock_guard lock(core_->mutex);
    id_ = core_->next_connection++;
}

HttpConnection::~HttpConnection() {
    core_->counters.open--;
    const std::lock_guard lock(core_->mutex);
    core_->waiting.erase(id_);
}

void HttpConnection::close_for_room() {
    asio::dispatch(stream_.get_executor(), [self = shared_from_this()] {
        boost::system::error_code ignored;
        self->stream_.socket().shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
        self->stream_.socket().close(ignored);
    });
}

void HttpConnection::start() {
    // On the connection's strand from the first step (the stream was made with one).
    asio::dispatch(stream_.get_executor(),
                   beast::bind_front_handler(&HttpConnection::read_request, shared_from_this()));
}

void HttpConnection::read_request() {
    parser_.emplace();
    parser_->body_limit(kMaxBodyBytes);
    parser_->header_limit(kMaxHeaderBytes);
    stream_.expires_after(kRequestTimeout);
    {
        const std::lock_guard lock(core_->mutex);
        core_->waiting[id_] = {Clock::now(), weak_from_this()};
    }
    bhttp::async_read(stream_, buffer_, *parser_,
                      [self = shared_from_this()](const boost::system::error_code& ec, std::size_t) {
                          self->on_read(ec);
                      });
}

void HttpConnection::on_read(const boost::system::error_code& ec) {
    {
        const std::lock_guard lock(core_->mutex);
        core_->waiting.erase(id_);
    }
    if (ec == bhttp::error::end_of_stream) {
        boost::system::error_code ignored;
        stream_.socket().shutdown(asio::ip::tcp::socket::shutdown_send, ignored);
        return;
    }
    if (ec == bhttp::error::body_limit) {
        Request head{bhttp::verb::post, "/", 11};
        TextResponse res = json_error(head, bhttp::status::payload_too_large,
                                      "a request body may have at most " +
                                          std::to_string(kMaxBodyBytes) +
                                          " bytes; jobs are submitted over the WebSocket");
        res.keep_alive(false);
        send(std::move(res));
        return;
    }
    if (ec) return;  // timed out or broken: the connection just ends
    Request req = parser_->release();
    if (websocket::is_upgrade(req)) {
        upgrade(std::move(req));
        return;
    }
    handle(std::move(req));
}

void HttpConnection::handle(Request&& req) {
    const std::string path = target_path(req);
    const bool get = req.method() == bhttp::verb::get || req.method() == bhttp::verb::head;
    const bool post = req.method() == bhttp::verb::post;

    if (path.rfind("/api/", 0) == 0) {
        if (path == "/api/login" && post) return send(login(*core_, req, address_, peer_));
        if (path == "/api/logout" && post) return send(logout(*core_, req));
        if (path == "/api/session" && get) return send(session_state(*core_, req));
        if (path == "/api/ws")
            return send(json_error(req, bhttp::status::bad_request,
                                   "/api/ws takes a WebSocket upgrade"));
        for (const auto& [prefix, resolve] : core_->file_routes) {
            if (path.rfind(prefix, 0) != 0 || !get) continue;
            if (!has_session(*core_, req)) {
                core_->counters.unauthorized++;
                return send(json_error(req, bhttp::status::unauthorized, "log in first"));
            }
            const std::string_view rest = std::string_view(path).substr(prefix.size());
            const auto slash = rest.find('/');
            std::optional<FileResponse> res;
            if (slash != std::string_view::npos)
                if (const auto folder = resolve(rest.substr(0, slash)))
                    if (const auto found = find_static_file(*folder, rest.substr(slash)))
                        res = file_response(req, found->path, found->content_type);
            if (!res) return send(json_error(req, bhttp::status::not_found, "no such file: " + path));
            return send(std::move(*res));
        }
        return send(json_error(req, bhttp::status::not_found, "no such API route: " + path));
    }

    if (!get)
        return send(json_error(req, bhttp::status::method_not_allowed,
                               "the dashboard's pages are read with GET"));
    const auto found = find_static_file(core_->web_root, path == "/" ? "/index.html" : path);
    std::optional<FileResponse> res;
    if (found) res = file_response(req, found->path, found->content_type);
    if (!res) return send(json_error(req, bhttp::status::not_found, "not found: " + path));
    if (req.method() == bhttp::verb::head) {
        bhttp::response<bhttp::empty_body> head{bhttp::status::ok, req.version()};
        add_common_headers(head, req);
        head.set(bhttp::field::content_type, found->content_type);
        head.content_length(res->body().size());
        return send(std::move(head));
    }
    send(std::move(*res));
}

void HttpConnection::upgrade(Request&& req) {
    if (target_path(req) != "/api/ws")
        return send(json_error(req, bhttp::status::not_found, "WebSockets are at /api/ws"));
    if (!has_session(*core_, req)) {
        core_->counters.unauthorized++;
        spdlog::warn("http.websocket_refused peer={}: no session (log in first)", peer_);
        return send(json_error(req, bhttp::status::unauthorized, "log in first"));
    }
    if (!same_origin(req)) {
        core_->counters.unauthorized++;
        spdlog::warn("http.websocket_refused peer={}: a page of another origin", peer_);
        return send(json_error(req, bhttp::status::forbidden, "a page of another origin"));
    }
    std::size_t max_line = 0;
    {
        const std::lock_guard lock(core_->mutex);
        max_line = core_->config.max_client_queue_bytes + kWebSocketSlack;
    }
    stream_.expires_never();  // the WebSocket's own pings decide from now on
    auto ws = std::make_shared<WebSocketBridge::Ws>(std::move(stream_));
    ws->set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws->set_option(websocket::stream_base::decorator(
        [](websocket::response_type& res) { res.set(bhttp::field::server, "fibrecelld"); }));
    // No limit of the WebSocket's own: the bridge passes a message on piece by piece and the
    // API's limit answers one that is too long (-32004), as on the socket.
    ws->read_message_max(0);
    auto self = shared_from_this();
    core_->counters.websockets++;
    ws->async_accept(req, [self, ws, max_line, session = session_id(req)](const boost::system::error_code& ec) {
        if (ec) return;
        spdlog::info("http.websocket peer={}", self->peer_);
        auto api = self->core_->api.open_bridge("websocket " + self->peer_,
                                                "dashboard " + self->address_);
        auto session_valid = [core = self->core_, id = session] {
            const std::lock_guard lock(core->mutex);
            return core->sessions.valid(id, Clock::now());
        };
        std::make_shared<WebSocketBridge>(std::move(*ws), std::move(api), max_line,
                                          std::move(session_valid))
            ->start();
    });
}

template <class Response>
void HttpConnection::send(Response&& response) {
    auto res = std::make_shared<std::decay_t<Response>>(std::forward<Response>(response));
    bhttp::async_write(stream_, *res,
                       [self = shared_from_this(), res](const boost::system::error_code& ec,
                                                        std::size_t) {
                           self->on_written(ec, res->need_eof());
                       });
}

void HttpConnection::on_written(const boost::system::error_code& ec, bool close) {
    if (ec) return;
    if (close) {
        boost::system::error_code ignored;
        stream_.socket().shutdown(asio::ip::tcp::socket::shutdown_send, ignored);
        return;
    }
    read_request();
}

}  // namespace fibrecell::http
