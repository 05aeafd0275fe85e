#pragma once
// The validator: structural and semantic checks of a parsed module (docs/rapid-subset.md lists
// every rule). Returns all diagnostics; never throws on a bad module.

#include <cstddef>
#include <string>
#include <vector>

#include "drivers/abb/rapid/diagnostic.hpp"
#include "drivers/abb/rapid/program.hpp"

namespace fibrecell::drivers::abb::rapid {

// Data declared in another module of the task (the resident main's PERS, for instance).
struct ExternalData {
    std::string name;
    std::string type;  // "num", "tooldata", ...
};

struct ValidateOptions {
    // Labels diagnostics; when set (and check_module_name), its stem must equal the module name.
    std::string file_name;
    bool check_module_name = true;
    // Chunk modules must stay below this many lines (RoboDK's default, docs/robot-program.md,
    // "The RAPID chunks").
    std::size_t max_lines = 5000;
    // Signals configured in the controller's I/O configuration (EIO), usable without declaration.
    std::vector<std::string> known_signals;
    // Routines of other modules this module may call: "Proc" (any module) or "Module:Proc".
    std::vector<std::string> external_routines;
    std::vector<ExternalData> external_data;
    // Modules already loaded in the task: this module's name must differ from all of them.
    std::vector<std::string> loaded_modules;
    double quaternion_tolerance = 1e-5;       // | |q| - 1 | allowed
    std::size_t min_quaternion_decimals = 6;  // digits after the point in quaternion literals
};

std::vector<Diagnostic> validate(const Module& module, const ValidateOptions& options = {});

}  // namespace fibrecell::drivers::abb::rapid
