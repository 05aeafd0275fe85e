#include "daemon/api/tcp_listener.hpp"

#include "daemon/api/api_server.hpp"

namespace fibrecell::api {

namespace asio = boost::asio;
using asio::ip::tcp;

std::unique_ptr<tcp::acceptor> listen_tcp(asio::io_context& io, const std::string& what,
                                          const std::string& host, std::uint16_t port) {
    const std::string where = what + " " + host + ":" + std::to_string(port);
    boost::system::error_code ec;
    const auto address = asio::ip::make_address(host, ec);
    if (ec) throw ApiStartError("cannot listen on " + where + ": not an IP address");
    const tcp::endpoint endpoint(address, port);
    auto acceptor = std::make_unique<tcp::acceptor>(io);
    acceptor->open(endpoint.protocol(), ec);
    if (!ec) acceptor->set_option(tcp::acceptor::reuse_address(true), ec);
    if (!ec) acceptor->bind(endpoint, ec);
    if (!ec) acceptor->listen(asio::socket_base::max_listen_connections, ec);
    if (ec) throw ApiStartError("cannot listen on " + where + ": " + ec.message());
    return acceptor;
}

}  // namespace fibrecell::api
