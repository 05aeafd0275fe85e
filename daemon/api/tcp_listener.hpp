#pragma once
// A listening TCP socket on host:port for the API's TCP transport and the dashboard's HTTP.

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>

#include <cstdint>
#include <memory>
#include <string>

namespace fibrecell::api {

// Bound (address reuse on) and listening; throws ApiStartError "cannot listen on <what>
// host:port: <reason>" (`what`: "TCP", "HTTP").
std::unique_ptr<boost::asio::ip::tcp::acceptor> listen_tcp(boost::asio::io_context& io,
                                                           const std::string& what,
                                                           const std::string& host,
                                                           std::uint16_t port);

}  // namespace fibrecell::api
