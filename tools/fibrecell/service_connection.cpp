#include "tools/fibrecell/service_connection.hpp"

#include <cstdlib>
#include <exception>
#include <iostream>

namespace fibrecell::tools {

namespace {
constexpr const char* default_socket = "/run/fibrecelld/api.sock";
}

api::ApiClient Connection::connect() const {
    api::ApiEndpoint e;
    e.socket_path = socket;
    e.host = host;
    e.port = port;
    e.token = token;
    return api::ApiClient::connect(e);
}

void add_connection_options(CLI::App& cmd, Connection& c) {
    if (const char* s = std::getenv("FIBRECELL_SOCKET")) c.socket = s;
    if (c.socket.empty()) c.socket = default_socket;
    if (const char* t = std::getenv("FIBRECELL_TOKEN")) c.token = t;
    cmd.add_option("--socket", c.socket, "the service's Unix socket ($FIBRECELL_SOCKET)");
    cmd.add_option("--host", c.host, "connect over TCP to this host instead");
    cmd.add_option("--port", c.port, "TCP port (with --host)");
    cmd.add_option("--token", c.token, "TCP token ($FIBRECELL_TOKEN)");
    cmd.add_flag("--json", c.json_output, "machine-readable output");
}

void guarded(int& exit_code, const std::function<int()>& body) {
    try {
        exit_code = body();
    } catch (const std::exception& e) {  // api::ApiCallError too: its text is the service's
        std::cerr << "fibrecell: " << e.what() << "\n";
        exit_code = 1;
    }
}

void print(const Connection& c, const nlohmann::json& answer, const std::string& human) {
    if (c.json_output)
        std::cout << answer.dump() << "\n";
    else
        std::cout << human;
}

}  // namespace fibrecell::tools
