#pragma once
// What every client verb shares: how it reaches the service (--socket, default
// $FIBRECELL_SOCKET then /run/fibrecelld/api.sock; --host/--port/--token for TCP), --json, and
// how an error ends it (one line on stderr, exit code 1).

#include "daemon/api/api_client.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <string>

namespace fibrecell::tools {

struct Connection {
    std::string socket, host, token;
    std::uint16_t port = 7420;
    bool json_output = false;

    api::ApiClient connect() const;
};

void add_connection_options(CLI::App& cmd, Connection& c);

// A verb's body; errors become one line on stderr and exit code 1.
void guarded(int& exit_code, const std::function<int()>& body);

// The answer as JSON with --json, else `human`.
void print(const Connection& c, const nlohmann::json& answer, const std::string& human);

}  // namespace fibrecell::tools
