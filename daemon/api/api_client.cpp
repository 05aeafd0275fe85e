#include "daemon/api/api_client.hpp"

#include "daemon/api/json_rpc.hpp"

#include <boost/asio/connect.hpp>
#include <boost/asio/generic/stream_protocol.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/local/stream_protocol.hpp>
#include <boost/asio/write.hpp>

#include <poll.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <deque>

namespace fibrecell::api {

namespace asio = boost::asio;
using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

ApiCallError::ApiCallError(int code, const std::string& message, nlohmann::json data)
    : std::runtime_error(message), code_(code), data_(std::move(data)) {}

struct ApiClient::Impl {
    asio::io_context io;
    asio::generic::stream_protocol::socket socket{io};
    std::string where;
    ApiClientOptions options;
    std::string inbuf;
    std::deque<ApiNotification> notifications;
    std::int64_t next_id = 1;
    bool eof = false;

    void connect_unix(const std::string& path);
    void connect_tcp(const std::string& host, std::uint16_t port);
    std::optional<nlohmann::json> read_message(Clock::time_point deadline);
    bool fill(Clock::time_point deadline);  // false on timeout
    void write(const std::string& line);
};

namespace {

std::string unix_connect_error(const boost::system::error_code& ec, const std::string& path) {
    namespace errc = boost::system::errc;
    if (ec == errc::no_such_file_or_directory)
        return "fibrecelld is not running (no socket at " + path + ")";
    if (ec == errc::connection_refused)
        return "fibrecelld is not running (stale socket at " + path + ")";
    if (ec == errc::permission_denied || ec == errc::operation_not_permitted)
        return "permission denied on " + path;
    if (ec == errc::not_a_directory)
        return "no socket at " + path + " (a parent is not a directory)";
    if (ec == errc::resource_unavailable_try_again)
        return "fibrecelld at " + path + " is overloaded (connection backlog full)";
    return "cannot connect to fibrecelld at " + path + ": " + ec.message();
}

int remaining_ms(Clock::time_point deadline) {
    const auto left = std::chrono::ceil<milliseconds>(deadline - Clock::now()).count();
    return static_cast<int>(std::clamp<std::int64_t>(left, 0, 1 << 30));
}

}  // namespace

void ApiClient::Impl::connect_unix(const std::string& path) {
    where = path;
    asio::local::stream_protocol::endpoint endpoint;
    try {
        endpoint = asio::local::stream_protocol::endpoint(path);
    } catch (const boost::system::system_error&) {
        throw ApiClientError("socket path is too long for a Unix socket: " + path);
    }
    boost::system::error_code ec;
    socket.connect(endpoint, ec);
    if (ec) throw ApiClientError(unix_connect_error(ec, path));
}

void ApiClient::Impl::connect_tcp(const std::string& host, std::uint16_t port) {
    where = host + ":" + std::to_string(port);
    boost::system::error_code ec;
    asio::ip::tcp::resolver resolver(io);
    const auto endpoints = resolver.resolve(host, std::to_string(port), ec);
    if (ec) throw ApiClientError("cannot resolve host " + host + ": " + ec.message());
    asio::ip::tcp::socket tcp_socket(io);
    bool done = false;
    asio::async_connect(tcp_socket, endpoints,
                        [&](const boost::system::error_code& e, const asio::ip::tcp::endpoint&) {
                            ec = e;
                            done = true;
                        });
    io.restart();
    io.run_for(options.connect_timeout);
    if (!done) {
        tcp_socket.close();
        io.restart();
        io.run();  // lets the cancelled connect finish
        throw ApiClientError("no answer from fibrecelld at " + where + " within " +
                             std::to_string(options.connect_timeout.count()) + " ms");
    }
    if (ec == boost::system::errc::connection_refused)
        throw ApiClientError("fibrecelld is not listening on " + where);
    if (ec) throw ApiClientError("cannot connect to fibrecelld at " + where + ": " + ec.message());
    tcp_socket.set_option(asio::ip::tcp::no_delay(true), ec);
    const auto protocol = asio::generic::stream_protocol(tcp_socket.local_endpoint().protocol());
    socket = asio::generic::stream_protocol::socket(io, protocol, tcp_socket.release());
}

bool ApiClient::Impl::fill(Clock::time_point deadline) {
    if (eof) throw ApiClientError("fibrecelld at " + where + " closed the connection");
    pollfd pfd{socket.native_handle(), POLLIN, 0};
    for (;;) {
        const int rc = ::poll(&pfd, 1, remaining_ms(deadline));
        if (rc > 0) break;
        if (rc == 0) return false;
        if (errno != EINTR) throw ApiClientError("cannot wait for fibrecelld at " + where);
    }
    std::array<char, 64 * 1024> chunk{};
    boost::system::error_code ec;
    const std::size_t n = socket.read_some(asio::buffer(chunk), ec);
    if (ec == asio::error::eof || ec == asio::error::connection_reset) {
        eof = true;
        throw ApiClientError("fibrecelld at " + where + " closed the connection");
    }
    if (ec) throw ApiClientError("cannot read from fibrecelld at " + where + ": " + ec.message());
    inbuf.append(chunk.data(), n);
    if (inbuf.size() > options.max_message_bytes)
        throw ApiClientError("fibrecelld at " + where + " sent a message above " +
                             std::to_string(options.max_message_bytes) + " bytes");
    return true;
}

std::optional<nlohmann::json> ApiClient::Impl::read_message(Clock::time_point deadline) {
    std::size_t scanned = 0;
    for (;;) {
        const auto nl = inbuf.find('\n', scanned);
        if (nl != std::string::npos) {
            const std::string line = inbuf.substr(0, nl);
            inbuf.erase(0, nl + 1);
            scanned = 0;
            if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
            try {
                return nlohmann::json::parse(line);
            } catch (const nlohmann::json::parse_error& e) {
                throw ApiClientError("fibrecelld at " + where +
                                     " sent malformed JSON: " + e.what());
            }
        }
        scanned = inbuf.size();
        if (!fill(deadline)) return std::nullopt;
    }
}

void ApiClient::Impl::write(const std::string& line) {
    boost::system::error_code ec;
    asio::write(socket, asio::buffer(line), ec);
    if (ec)
        throw ApiClientError("fibrecelld at " + where + " closed the connection (" + ec.message() +
                             ")");
}

ApiClient::ApiClient(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ApiClient::ApiClient(ApiClient&&) noexcept = default;
ApiClient& ApiClient::operator=(ApiClient&&) noexcept = default;
ApiClient::~ApiClient() = default;

ApiClient ApiClient::connect(const ApiEndpoint& endpoint, ApiClientOptions options) {
    auto impl = std::make_unique<Impl>();
    impl->options = options;
    if (endpoint.host.empty()) {
        impl->connect_unix(endpoint.socket_path);
        return ApiClient(std::move(impl));
    }
    impl->connect_tcp(endpoint.host, endpoint.port);
    ApiClient client(std::move(impl));
    // Without a token the service answers the first call with "unauthorized".
    if (!endpoint.token.empty())
        client.call("server.auth", {{"token", endpoint.token}}, options.connect_timeout);
    return client;
}

nlohmann::json ApiClient::call(const std::string& method, nlohmann::json params,
                               std::optional<milliseconds> timeout) {
    const milliseconds limit = timeout.value_or(impl_->options.call_timeout);
    const auto deadline = Clock::now() + limit;
    const std::int64_t id = impl_->next_id++;
    impl_->write(to_line(request_message(id, method, std::move(params))));
    for (;;) {
        auto message = impl_->read_message(deadline);
        if (!message)
            throw ApiClientError("no answer to " + method + " from fibrecelld at " + impl_->where +
                                 " within " + std::to_string(limit.count()) + " ms");
        if (!message->is_object()) continue;  // a batch answer: not ours
        const auto id_it = message->find("id");
        if (id_it == message->end()) {
            if (message->contains("method"))
                impl_->notifications.push_back(
                    {message->value("method", ""), message->value("params", nlohmann::json())});
            continue;
        }
        const bool ours = *id_it == id;
        if (!ours && !id_it->is_null()) continue;  // a late answer to an earlier, timed-out call
        if (const auto error = message->find("error"); error != message->end()) {
            throw ApiCallError(error->value("code", 0), error->value("message", ""),
                               error->value("data", nlohmann::json()));
        }
        if (ours) return message->value("result", nlohmann::json());
    }
}

void ApiClient::notify(const std::string& method, nlohmann::json params) {
    impl_->write(to_line(notification_message(method, std::move(params))));
}

std::optional<ApiNotification> ApiClient::next_notification(milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    for (;;) {
        if (!impl_->notifications.empty()) {
            ApiNotification n = std::move(impl_->notifications.front());
            impl_->notifications.pop_front();
            return n;
        }
        auto message = impl_->read_message(deadline);
        if (!message) return std::nullopt;
        if (message->is_object() && !message->contains("id") && message->contains("method"))
            impl_->notifications.push_back(
                {message->value("method", ""), message->value("params", nlohmann::json())});
    }
}

void ApiClient::send_line(std::string line) {
    if (line.empty() || line.back() != '\n') line.push_back('\n');
    impl_->write(line);
}

std::optional<nlohmann::json> ApiClient::read_message(milliseconds timeout) {
    return impl_->read_message(Clock::now() + timeout);
}

bool ApiClient::wait_closed(milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    try {
        for (;;) {
            impl_->inbuf.clear();
            if (!impl_->fill(deadline)) return false;
        }
    } catch (const ApiClientError&) {
        return impl_->eof;
    }
}

const std::string& ApiClient::describe() const {
    return impl_->where;
}

}  // namespace fibrecell::api
