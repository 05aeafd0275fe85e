#pragma once
// Internal: one HTTP connection of the dashboard's listener: keep-alive requests, each answered
// from the routes in http_routes.cpp, until it upgrades to a WebSocket or ends.

#include "daemon/http/http_core.hpp"

#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/http/parser.hpp>
#include <boost/beast/http/string_body.hpp>

#include <memory>
#include <optional>
#include <string>

namespace fibrecell::http {

using Request = boost::beast::http::request<boost::beast::http::string_body>;

class HttpConnection : public std::enable_shared_from_this<HttpConnection> {
  public:
    HttpConnection(std::shared_ptr<HttpCore> core, boost::asio::ip::tcp::socket socket);
    ~HttpConnection();
    HttpConnection(const HttpConnection&) = delete;
    HttpConnection& operator=(const HttpConnection&) = delete;
    void start();
    // Ends the connection (on its own strand) to make room for a newer one.
    void close_for_room();

  private:
    void read_request();
    void on_read(const boost::system::error_code& ec);
    void handle(Request&& req);
    void upgrade(Request&& req);
    template <class Response>
    void send(Response&& response);
    void on_written(const boost::system::error_code& ec, bool close);

    std::shared_ptr<HttpCore> core_;
    boost::beast::tcp_stream stream_;
    boost::beast::flat_buffer buffer_;
    std::optional<boost::beast::http::request_parser<boost::beast::http::string_body>> parser_;
    std::string address_;  // the client's IP, for the login limit and logs
    std::string peer_;     // "address:port"
    std::uint64_t id_ = 0;  // HttpCore::waiting's key
};

}  // namespace fibrecell::http
