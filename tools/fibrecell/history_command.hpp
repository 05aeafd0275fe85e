#pragma once
// `fibrecell history [--since DATE] [--limit N] [--json|--csv]`: the jobs the cell ended, with
// what they used (docs/history.md). --csv writes the service's CSV as it is (RFC 4180, for a
// spreadsheet: `fibrecell history --csv > history.csv`).

#include <CLI/CLI.hpp>

namespace fibrecell::tools {

void add_history_command(CLI::App& app, int& exit_code);

}  // namespace fibrecell::tools
