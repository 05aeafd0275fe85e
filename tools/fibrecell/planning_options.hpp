#pragma once
// The options every offline planning command shares (`plan`, `compare`).

#include <CLI/CLI.hpp>

#include <string>

namespace fibrecell::tools {

// --threads (layer workers, 0: all cores) and --cell (the cell YAML the plan is for).
inline void add_planning_options(CLI::App* cmd, int& threads, std::string& cell) {
    cmd->add_option("--threads", threads, "worker threads for the layers (default: all cores)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--cell", cell,
                    "cell YAML of the cell that will print it (default: the simulated cell)")
        ->check(CLI::ExistingFile);
}

}  // namespace fibrecell::tools
