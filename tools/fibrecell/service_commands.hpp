#pragma once
// The client verbs of the jobs and the cell that talk to fibrecelld over the socket API
// (docs/contracts.md "Commands"): submit, jobs, status, start, pause, resume, abort, remove,
// replan, watch, estop (the queue's: queue_commands.hpp). Each takes the connection options of
// service_connection.hpp and --json; human output by default, one clear line and a non-zero exit
// code on error.

#include <CLI/CLI.hpp>

namespace fibrecell::tools {

void add_service_commands(CLI::App& app, int& exit_code);

}  // namespace fibrecell::tools
