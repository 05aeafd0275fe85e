#pragma once
// RAPID names: identifiers are case-insensitive (docs/rapid-subset.md, "Lexical elements"), so
// every comparison goes through fold(); the reserved words and built-in function names that no
// declaration may take.

#include <cstddef>
#include <string>
#include <string_view>

namespace fibrecell::drivers::abb::rapid {

// Identifiers longer than this are rejected by the controller (RAPID spec. section 2.3).
inline constexpr std::size_t max_identifier_length = 32;
// String literals and string values longer than this are rejected (RAPID spec. section 2.13).
inline constexpr std::size_t max_string_length = 80;

// Lower-case ASCII copy: the key under which a name is looked up.
std::string fold(std::string_view name);
bool same_name(std::string_view a, std::string_view b);

// Letter first, then letters, digits and '_' (the length limit is a separate rule).
bool is_identifier(std::string_view text);

// The reserved words of docs/rapid-subset.md (AND ... XOR), case-insensitive.
bool is_reserved_word(std::string_view name);

// Built-in functions the reader knows by name (Offs, NumToStr, DInput, CRobT, ...). A call to one
// of them needs no declaration; some are evaluated by evaluate() (see evaluate.hpp).
bool is_builtin_function(std::string_view name);

// The data type a known built-in function returns ("" when unknown or when it depends on args).
std::string_view builtin_function_type(std::string_view name);

}  // namespace fibrecell::drivers::abb::rapid
