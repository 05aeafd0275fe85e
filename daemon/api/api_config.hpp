#pragma once
// The `api:` section of the cell YAML: where the socket API listens and its limits
// (docs/socket-api.md). Read once at start-up and again on SIGHUP.
//
//   api:
//     socket: /run/fibrecelld/api.sock
//     socket_mode: "0660"       # octal; who may connect is decided by mode and group
//     socket_group: fibrecell   # optional: name or numeric gid
//     max_request_bytes: 16777216
//     tcp: {enabled: true, host: 127.0.0.1, port: 7420, token_file: /etc/fibrecelld/api.token}
//     http: {enabled: true, port: 7480, token_file: /etc/fibrecelld/dashboard.token}

#include "config/yaml_section.hpp"

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

namespace fibrecell::api {

struct ApiTcpConfig {
    bool enabled = false;
    std::string host = "127.0.0.1";  // an IP address; loopback unless told otherwise
    std::uint16_t port = 7420;       // 0: an ephemeral port (the tests), see ApiServer::tcp_port()
    std::string token;               // from `token` or the first line of `token_file`
    std::chrono::milliseconds auth_timeout{10000};  // a connection must call server.auth by then
    // Connections still to call server.auth, at most: beyond it the oldest of them is closed
    // (connections that never authenticate cannot fill the server).
    int max_unauthenticated = 8;
    // Tokens checked per second, all connections together: beyond it server.auth is answered
    // "try again" without a check, so that guessing the token is bounded whatever the number of
    // connections (a burst of as many is allowed).
    int auth_attempts_per_s = 10;
};

// The dashboard's HTTP listener (daemon/http, docs/dashboard.md): the pages, a login with a
// token of its own (a session cookie), and a WebSocket that speaks this API.
struct ApiHttpConfig {
    bool enabled = false;
    std::string host = "127.0.0.1";  // loopback: reach it from elsewhere through a TLS proxy
    std::uint16_t port = 7480;       // 0 (tests only): an ephemeral port
    std::string token;               // from `token` or the first line of `token_file`
    std::string web_root;            // the pages' folder; "" for the installed or built ones
    std::chrono::seconds session_lifetime{12 * 3600};  // a login lasts this long
    int login_failures_per_minute = 5;  // per client address; beyond it logins wait
    bool secure_cookie = false;         // behind an https proxy: the cookie only over TLS
};

struct ApiConfig {
    std::string socket_path = "/run/fibrecelld/api.sock";
    unsigned socket_mode = 0660;  // permission bits of the socket file
    std::string socket_group;     // group name or numeric gid; "" keeps the process's group
    ApiTcpConfig tcp;
    ApiHttpConfig http;
    std::size_t max_request_bytes = std::size_t{16} << 20;  // one request line; jobs carry files
    int max_clients = 64;                                   // connections at once, both transports
    // Connections admitted beyond max_clients that may call only the control methods
    // (ApiServer::add_control_method: status, pause, abort, estop): a few idle or hostile clients
    // never take those from the operator.
    int reserved_control_clients = 4;
    // A connection that sends no request for this long and subscribes to nothing is closed
    // (0: never). Connections in the reserved capacity get at most control_idle_timeout.
    std::chrono::milliseconds idle_timeout{300000};
    std::chrono::milliseconds control_idle_timeout{10000};
    double progress_rate_hz = 2.0;  // latest-only events per topic per client, at most this often
    // Outgoing bytes a client may leave unread before it is disconnected (a slow subscriber
    // never holds the service back). A single message larger than this still goes out.
    std::size_t max_client_queue_bytes = std::size_t{32} << 20;
    // Calls in one batch: one batch is handled in one go, so a huge one would hold everyone
    // else's calls back. Its answers together must fit in max_client_queue_bytes.
    int max_batch_calls = 1000;
};

// Reads and checks the section (ranges, octal mode, group exists, token or token_file readable,
// unknown keys); throws config::ConfigError naming the key.
ApiConfig load_api_config(config::Section s);
// The same for a bare `api:` node; `origin` names the file in messages.
ApiConfig load_api_config(const YAML::Node& node, const std::string& origin);

// The token on the first line of `path` (surrounding blanks dropped); throws std::runtime_error
// naming the file when it cannot be read or the token is shorter than 16 characters.
std::string read_token_file(const std::string& path);

// Parses an octal file mode ("0660", "660", "0o660"); returns false when it is not one (<= 0777).
bool parse_octal_mode(const std::string& text, unsigned& mode);

}  // namespace fibrecell::api
