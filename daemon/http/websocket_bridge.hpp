#pragma once
// Internal: one dashboard WebSocket joined to its ApiServer client (ApiServer::open_bridge). Each
// text message from the browser becomes one request line (passed on piece by piece); each line the API sends (answers and
// notifications) becomes one message. One message in flight each way: a browser that stops
// reading backs up into the API's own per-client queue, which drops it at its limit.

#include <boost/asio/local/stream_protocol.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/websocket/stream.hpp>

#include <functional>
#include <memory>
#include <string>

namespace fibrecell::http {

class WebSocketBridge : public std::enable_shared_from_this<WebSocketBridge> {
  public:
    using Ws = boost::beast::websocket::stream<boost::beast::tcp_stream>;
    using Local = boost::asio::local::stream_protocol::socket;

    // `max_line`: the longest line the API may send (its per-client queue limit). `session_valid`
    // is asked before every message either way: a logout, an expired login or a new token ends
    // the WebSocket at its next message (a watcher's next event: within a second).
    WebSocketBridge(Ws ws, Local api, std::size_t max_line, std::function<bool()> session_valid);
    void start();

  private:
    void read_browser();
    void on_browser_piece(const boost::system::error_code& ec);
    void read_api();
    void on_api_line(const boost::system::error_code& ec, std::size_t n);
    void close_browser(boost::beast::websocket::close_code code);
    void finish();

    Ws ws_;
    Local api_;
    std::size_t max_line_;
    std::function<bool()> session_valid_;
    boost::beast::flat_buffer from_browser_;
    std::string to_api_;
    std::string from_api_;
    std::string to_browser_;
    bool done_ = false;
};

}  // namespace fibrecell::http
