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

// `token` or the first line of `token_file` (either may be absent: "").
std::string read_token(config::Section& s) {
    const bool has_token = s.has("token");
    const bool has_file = s.has("token_file");
    if (has_token && has_file) s.fail("token_file", "give token or token_file, not both");
    std::string token;
    if (has_token) {
        token = s.get<std::string>("token");
        if (token.size() < kMinTokenChars)
            s.fail("token", "must be at least " + std::to_string(kMinTokenChars) +
                                " characters (e.g. `openssl rand -hex 16`)");
    } else if (has_file) {
        try {
            token = read_token_file(s.get<std::string>("token_file"));
        } catch (const std::runtime_error& e) {
            s.fail("token_file", e.what());
        }
    } else {
        s.get_or<std::string>("token", "");  // mark both keys as known
        s.get_or<std::string>("token_file", "");
    }
    return token;
}

std::string ip_address(config::Section& s, const std::string& fallback) {
    std::string host = s.get_or<std::string>("host", fallback);
    boost::system::error_code ec;
    boost::asio::ip::make_address(host, ec);
    if (ec) s.fail("host", "must be an IP address (127.0.0.1, ::1, 0.0.0.0), got '" + host + "'");
    return host;
}

void load_http(config::Section s, ApiHttpConfig& http) {
    http.enabled = s.get_or<bool>("enabled", http.enabled);
    http.host = ip_address(s, http.host);
    http.port = static_cast<std::uint16_t>(s.integer("port", http.port, 0, 65535));
    http.token = read_token(s);
    if (s.has("web_root")) http.web_root = s.path_or("web_root", "");
    http.session_lifetime = std::chrono::seconds(static_cast<long>(
        3600 * s.number("session_hours", 12, 0.01, 24 * 30)));
    http.login_failures_per_minute =
        s.integer("login_failures_per_minute", http.login_failures_per_minute, 1, 1000);
    http.secure_cookie = s.get_or<bool>("secure_cookie", http.secure_cookie);
    if (http.enabled && http.token.empty())
        s.fail("enabled", "the dashboard needs a token: set http.token or http.token_file");
    s.finish();
}

void load_tcp(config::Section s, ApiTcpConfig& tcp) {
    tcp.enabled = s.get_or<bool>("enabled", tcp.enabled);
    tcp.host = ip_address(s, tcp.host);
    tcp.port = static_cast<std::uint16_t>(s.integer("port", tcp.port, 0, 65535));
    tcp.auth_timeout = std::chrono::milliseconds(
        s.integer("auth_timeout_ms", static_cast<int>(tcp.auth_timeout.count()), 100, 600000));
    tcp.max_unauthenticated = s.integer("max_unauthenticated", tcp.max_unauthenticated, 1, 10000);
    tcp.auth_attempts_per_s = s.integer("auth_attempts_per_s", tcp.auth_attempts_per_s, 1, 10000);

    tcp.token = read_token(s);
    if (tcp.enabled && tcp.token.empty())
        s.fail("enabled", "TCP needs a token: set tcp.token or tcp.token_file");
    s.finish();
}

}  // namespace

std::string read_token_file(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read " + path + ": " + std::strerror(errno));
    std::string line;
    std::getline(in, line);
    std::string token = trim(line);
    if (token.size() < kMinTokenChars)
        throw std::runtime_error(path + ": the token on its first line must be at least " +
                                 std::to_string(kMinTokenChars) + " characters");
    return token;
}

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
    load_http(s.section("http"), c.http);
    s.finish();
    return c;
}

ApiConfig load_api_config(const YAML::Node& node, const std::string& origin) {
    return load_api_config(
        config::Section(node, "api", std::make_shared<const std::string>(origin)));
}

}  // namespace fibrecell::api
