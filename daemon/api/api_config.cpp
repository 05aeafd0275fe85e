#include "daemon/api/api_config.hpp"

#include <grp.h>
#include <sys/un.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include <boost/asio/ip/address.hpp>

namespace fibrecell::api {

namespace {

constexpr std::size_t kMinTokenChars = 16;

bool group_exists(const std::string& group) {
    const bool numeric = group.find_first_not_of("0123456789") == std::string::npos;
    if (numeric) return true;  // a gid need not have a name
    return getgrnam(group.c_str()) != nullptr;
}

std::string trim(std::string s) {
    const auto first = s.find_first_not_of(" \t\r\n");
    if (first == std::string::npos) return "";
    const auto last = s.find_last_not_of(" \t\r\n");
    return s.substr(first, last - first + 1);
}

void load_tcp(config::Section s, ApiTcpConfig& tcp) {
    tcp.enabled = s.get_or<bool>("enabled", tcp.enabled);
    tcp.host = s.get_or<std::string>("host", tcp.host);
    boost::system::error_code ec;
    boost::asio::ip::make_address(tcp.host, ec);
    if (ec)
        s.fail("host", "must be an IP address (127.0.0.1, ::1, 0.0.0.0), got '" + tcp.host + "'");
    tcp.port = static_cast<std::uint16_t>(s.integer("port", tcp.port, 1, 65535));
    tcp.auth_timeout = std::chrono::milliseconds(
        s.integer("auth_timeout_ms", static_cast<int>(tcp.auth_timeout.count()), 100, 600000));

    const bool has_token = s.has("token");
    const bool has_file = s.has("token_file");
    if (has_token && has_file) s.fail("token_file", "give token or token_file, not both");
    if (has_token) {
        tcp.token = s.get<std::string>("token");
        if (tcp.token.size() < kMinTokenChars)
            s.fail("token", "must be at least " + std::to_string(kMinTokenChars) +
                                " characters (e.g. `openssl rand -hex 16`)");
    } else if (has_file) {
        const auto path = s.get<std::string>("token_file");
        std::ifstream in(path);
        if (!in) s.fail("token_file", "cannot read " + path + ": " + std::strerror(errno));
        std::string line;
        std::getline(in, line);
        tcp.token = trim(line);
        if (tcp.token.size() < kMinTokenChars)
            s.fail("token_file", path + ": the token on its first line must be at least " +
                                     std::to_string(kMinTokenChars) + " characters");
    } else {
        s.get_or<std::string>("token", "");  // mark both keys as known
        s.get_or<std::string>("token_file", "");
    }
    if (tcp.enabled && tcp.token.empty())
        s.fail("enabled", "TCP needs a token: set tcp.token or tcp.token_file");
    s.finish();
}

}  // namespace

bool parse_octal_mode(const std::string& text, unsigned& mode) {
    std::string digits = text;
    if (digits.rfind("0o", 0) == 0 || digits.rfind("0O", 0) == 0) digits = digits.substr(2);
    if (digits.empty() || digits.size() > 4) return false;
    unsigned value = 0;
    for (char ch : digits) {
        if (ch < '0' || ch > '7') return false;
        value = value * 8 + static_cast<unsigned>(ch - '0');
    }
    if (value > 0777) return false;
    mode = value;
    return true;
}

ApiConfig load_api_config(config::Section s) {
    ApiConfig c;
    c.socket_path = s.path_or("socket", c.socket_path);
    constexpr std::size_t max_path = sizeof(sockaddr_un{}.sun_path) - 1;
    if (c.socket_path.size() > max_path)
        s.fail("socket", "is " + std::to_string(c.socket_path.size()) +
                             " bytes long; a Unix socket path may have at most " +
                             std::to_string(max_path));

    if (s.has("socket_mode")) {
        const YAML::Node n = s.node("socket_mode");
        if (!n.IsScalar() || !parse_octal_mode(n.Scalar(), c.socket_mode))
            s.fail("socket_mode", "must be an octal file mode such as \"0660\", got '" +
                                      (n.IsScalar() ? n.Scalar() : std::string("a non-scalar")) +
                                      "'");
    } else {
        s.node("socket_mode");
    }
    c.socket_group = s.get_or<std::string>("socket_group", "");
    if (!c.socket_group.empty() && !group_exists(c.socket_group))
        s.fail("socket_group", "no group '" + c.socket_group + "' on this system");

    c.max_request_bytes = static_cast<std::size_t>(
        s.integer("max_request_bytes", static_cast<int>(c.max_request_bytes), 1024, 1 << 30));
    c.max_clients = s.integer("max_clients", c.max_clients, 1, 10000);
    c.reserved_control_clients =
        s.integer("reserved_control_clients", c.reserved_control_clients, 0, 100);
    c.idle_timeout = std::chrono::milliseconds(
        static_cast<long>(1000 * s.number("idle_timeout_s", 300, 0, 86400)));
    c.progress_rate_hz = s.number("progress_rate_hz", c.progress_rate_hz, 0.0, 100.0, true);
    c.max_client_queue_bytes = static_cast<std::size_t>(s.integer(
        "max_client_queue_bytes", static_cast<int>(c.max_client_queue_bytes), 64 << 10, 1 << 30));
    c.max_batch_calls = s.integer("max_batch_calls", c.max_batch_calls, 1, 100000);
    load_tcp(s.section("tcp"), c.tcp);
    s.finish();
    return c;
}

ApiConfig load_api_config(const YAML::Node& node, const std::string& origin) {
    return load_api_config(
        config::Section(node, "api", std::make_shared<const std::string>(origin)));
}

}  // namespace fibrecell::api
