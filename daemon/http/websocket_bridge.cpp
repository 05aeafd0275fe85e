#include "daemon/http/websocket_bridge.hpp"

#include <boost/asio/bind_executor.hpp>
#include <boost/asio/read_until.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core/buffers_to_string.hpp>

namespace fibrecell::http {

namespace {

constexpr std::size_t kPieceBytes = 64 * 1024;

}  // namespace

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace websocket = beast::websocket;

WebSocketBridge::WebSocketBridge(Ws ws, Local api, std::size_t max_line,
                                 std::function<bool()> session_valid)
    : ws_(std::move(ws)),
      api_(std::move(api)),
      max_line_(max_line),
      session_valid_(std::move(session_valid)) {}

void WebSocketBridge::start() {
    read_browser();
    read_api();
}

// The browser's messages go to the API as they arrive, a piece at a time, never held whole:
// the API's own limit decides (a request over api.max_request_bytes is answered -32004 there and
// the answer comes back here), so a message of any size costs this bridge one piece of memory.
void WebSocketBridge::read_browser() {
    ws_.async_read_some(from_browser_, kPieceBytes,
                        [self = shared_from_this()](const boost::system::error_code& ec, std::size_t) {
                            self->on_browser_piece(ec);
                        });
}

void WebSocketBridge::on_browser_piece(const boost::system::error_code& ec) {
    // The browser closed or broke the connection, or its login ended: the API client goes too
    // (an answer may be on its way to the browser, so no closing handshake here).
    if (ec || done_ || !session_valid_()) {
        finish();
        return;
    }
    to_api_ = beast::buffers_to_string(from_browser_.data());
    from_browser_.clear();
    // The API frames requests by line. A raw line break in valid JSON is whitespace between
    // tokens (inside a string it must be escaped), so a pretty-printed request means the same.
    for (char& c : to_api_)
        if (c == '\n' || c == '\r') c = ' ';
    if (ws_.is_message_done()) to_api_ += '\n';
    asio::async_write(api_, asio::buffer(to_api_),
                      asio::bind_executor(ws_.get_executor(),
                                          [self = shared_from_this()](
                                              const boost::system::error_code& wec, std::size_t) {
                                              if (wec) return self->finish();
                                              self->read_browser();
                                          }));
}

void WebSocketBridge::read_api() {
    asio::async_read_until(
        api_, asio::dynamic_buffer(from_api_, max_line_), '\n',
        asio::bind_executor(ws_.get_executor(), [self = shared_from_this()](
                                                    const boost::system::error_code& ec,
                                                    std::size_t n) { self->on_api_line(ec, n); }));
}

void WebSocketBridge::on_api_line(const boost::system::error_code& ec, std::size_t n) {
    if (done_) return;
    if (ec) {
        close_browser(websocket::close_code::normal);  // the API closed this client
        return;
    }
    if (!session_valid_()) {
        close_browser(websocket::close_code::policy_error);  // logged out, expired, new token
        return;
    }
    to_browser_.assign(from_api_, 0, n - 1);
    from_api_.erase(0, n);
    ws_.text(true);
    ws_.async_write(asio::buffer(to_browser_),
                    [self = shared_from_this()](const boost::system::error_code& wec, std::size_t) {
                        if (wec) return self->finish();
                        self->read_api();
                    });
}

void WebSocketBridge::close_browser(websocket::close_code code) {
    ws_.async_close(code,
                    [self = shared_from_this()](const boost::system::error_code&) { self->finish(); });
}

void WebSocketBridge::finish() {
    if (done_) return;
    done_ = true;
    boost::system::error_code ignored;
    api_.close(ignored);
    beast::get_lowest_layer(ws_).close();
}

}  // namespace fibrecell::http
