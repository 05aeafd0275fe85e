#include "daemon/http/websocket_bridge.hpp"

#include <boost/asio/bind_executor.hpp>
#include <boost/asio/read_until.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core/buffers_to_string.hpp>

namespace fibrecell::http {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace websocket = beast::websocket;

WebSocketBridge::WebSocketBridge(Ws ws, Local api, std::size_t max_line)
    : ws_(std::move(ws)), api_(std::move(api)), max_line_(max_line) {}

void WebSocketBridge::start() {
    read_browser();
    read_api();
}

void WebSocketBridge::read_browser() {
    ws_.async_read(from_browser_,
                   [self = shared_from_this()](const boost::system::error_code& ec, std::size_t) {
                       self->on_browser_message(ec);
                   });
}

void WebSocketBridge::on_browser_message(const boost::system::error_code& ec) {
    if (ec || done_) {
        finish();  // the browser closed or broke the connection: the API client goes with it
        return;
    }
    to_api_ = beast::buffers_to_string(from_browser_.data());
    from_browser_.clear();
    // The API frames requests by line. A raw line break in valid JSON is whitespace between
    // tokens (inside a string it must be escaped), so a pretty-printed request means the same.
    for (char& c : to_api_)
        if (c == '\n' || c == '\r') c = ' ';
    to_api_ += '\n';
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
        close_browser();  // the API closed this client (stop, idle, an error it answered)
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

void WebSocketBridge::close_browser() {
    ws_.async_close(websocket::close_code::normal,
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
