#pragma once
// `fibrecell plan JOB.yaml --out DIR`: plans offline, in-process, and writes the plan directory.

#include <CLI/CLI.hpp>

namespace fibrecell::tools {

// Adds the `plan` subcommand to `app`; the callback sets `exit_code`.
void add_plan_command(CLI::App& app, int& exit_code);

}  // namespace fibrecell::tools
