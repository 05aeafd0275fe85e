#pragma once
// The client verbs that talk to fibrecelld over the socket API (docs/contracts.md "Commands"):
// submit, jobs, status, start, pause, resume, abort, remove, watch, estop. Each takes --socket
// (default $FIBRECELL_SOCKET, then /run/fibrecelld/api.sock), --host/--port/--token for TCP and
// --json; human output by default, one clear line and a non-zero exit code on error.

#include <CLI/CLI.hpp>

namespace fibrecell::tools {

void add_service_commands(CLI::App& app, int& exit_code);

}  // namespace fibrecell::tools
