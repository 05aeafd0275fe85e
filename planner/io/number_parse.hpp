#pragma once
// Whole-token number parsing and small text helpers shared by the file readers.

#include <optional>
#include <string>
#include <string_view>

namespace fibrecell::planner {

// The integer spelled by all of `text` (optional leading sign), or nullopt.
std::optional<long long> parse_integer(std::string_view text);

// The floating-point number spelled by all of `text` (optional leading sign, exponent), or
// nullopt. "nan" and "inf" parse as such: callers decide how to reject them. Values beyond the
// double range are nullopt.
std::optional<double> parse_real(std::string_view text);

// ASCII case-insensitive equality (file keywords, array names).
bool iequals(std::string_view a, std::string_view b);

// `text` with surrounding blanks (space, tab, CR) removed.
std::string_view trim(std::string_view text);

// A token as it may be quoted in an error message: at most 40 characters, control bytes as '?'.
std::string shown(std::string_view token);

}  // namespace fibrecell::planner
