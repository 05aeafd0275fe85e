#pragma once
// The RAPID reader's front door: read a module (text or file), parse it into the program model and
// validate it. check_* return every diagnostic; read_* throw RapidError on the first error.
//
//   ValidateOptions o;
//   o.file_name = "Print_0001.mod";
//   o.known_signals = {"goEvent", "doExtrude", "diReady"};
//   const CheckResult r = check_module(text, o);
//   for (const Diagnostic& d : r.diagnostics) log(format(d));
//   if (r.ok()) for (const MoveTarget& t : move_targets(*r.module)) check_reach(t);

#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

#include "drivers/abb/rapid/diagnostic.hpp"
#include "drivers/abb/rapid/evaluate.hpp"
#include "drivers/abb/rapid/move_targets.hpp"
#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/parser.hpp"
#include "drivers/abb/rapid/predefined.hpp"
#include "drivers/abb/rapid/program.hpp"
#include "drivers/abb/rapid/robot_data.hpp"
#include "drivers/abb/rapid/validate.hpp"

namespace fibrecell::drivers::abb::rapid {

struct CheckResult {
    std::optional<Module> module;         // absent when the text could not be parsed
    std::vector<Diagnostic> diagnostics;  // lexical, syntax and validation, sorted by line

    bool ok() const { return module.has_value() && !has_errors(diagnostics); }
};

// Parse and validate; options.file_name labels diagnostics and names the expected module.
CheckResult check_module(std::string_view text, const ValidateOptions& options = {});

// Reads the file (binary, so line ends and bytes are checked as stored); file_name defaults to
// the path's file name. A file that cannot be read gives a diagnostic at line 0.
CheckResult check_module_file(const std::filesystem::path& path, ValidateOptions options = {});

// The same, throwing RapidError for the first error (warnings pass).
Module read_module(std::string_view text, const ValidateOptions& options = {});
Module read_module_file(const std::filesystem::path& path, ValidateOptions options = {});

}  // namespace fibrecell::drivers::abb::rapid
