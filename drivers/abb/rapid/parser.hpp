#pragma once
// RAPID text to the program model (program.hpp): the subset of docs/rapid-subset.md. Parsing stops
// at the first syntax or block error (one clear message beats a cascade); lexical problems and
// misplaced declarations are reported without stopping. Never throws on bad input.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "drivers/abb/rapid/diagnostic.hpp"
#include "drivers/abb/rapid/program.hpp"

namespace fibrecell::drivers::abb::rapid {

struct ParseOptions {
    std::string file_name;         // labels diagnostics and Module::file; may be empty
    std::size_t max_nesting = 64;  // deeper expressions or blocks are rejected (nesting-depth)
};

struct ParseResult {
    std::optional<Module> module;  // present unless a syntax or block error stopped the parser
    std::vector<Diagnostic> diagnostics;
};

// Parses one module. Declarations get their `value` (and `extents`) when the initialiser is a
// constant the reader can evaluate; see validate() for everything beyond the grammar.
ParseResult parse_module(std::string_view text, const ParseOptions& options = {});

}  // namespace fibrecell::drivers::abb::rapid
