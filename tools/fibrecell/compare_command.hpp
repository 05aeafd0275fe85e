#pragma once
// `fibrecell compare JOB.yaml --out DIR`: what the fibres buy, strategy against strategy. Plans
// the job with the field strategy, then with contour-zigzag held to the same fibre per layer
// (planner.fibre_budget), and prints the predicted stiffness of the bare part and both
// reinforced ones side by side (DIR/field/, DIR/contour-zigzag/, DIR/compare.json).

#include <CLI/CLI.hpp>

namespace fibrecell::tools {

// Adds the `compare` subcommand to `app`; the callback sets `exit_code`.
void add_compare_command(CLI::App& app, int& exit_code);

}  // namespace fibrecell::tools
