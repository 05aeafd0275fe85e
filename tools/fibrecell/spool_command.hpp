#pragma once
// `fibrecell spool [--json]`: the spool on each hotend, what is left and what the queue needs;
// `fibrecell spool load T1 --material "CF 1K" --length 250m [--tow 1K] [--lot A17]
// [--diameter MM]` (or `--mass 500g --density 1.5 --diameter 1.75`); `fibrecell spool unload T1`
// (docs/spools.md).

#include <CLI/CLI.hpp>

#include <string>

namespace fibrecell::tools {

void add_spool_command(CLI::App& app, int& exit_code);

// "250m", "250 m", "2500mm", "0.5 km" -> millimetres; throws std::invalid_argument naming the
// text for anything else (a bare number says no unit: refused).
double length_mm(const std::string& text);
// "500g", "500 g", "0.5kg" -> grams.
double mass_g(const std::string& text);

}  // namespace fibrecell::tools
