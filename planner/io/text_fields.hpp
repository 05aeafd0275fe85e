#pragma once
// Splitting one line of a delimited text file (the reference data's ',' and ':' formats).

#include <cstddef>
#include <string_view>

namespace fibrecell::planner {

// Splits `line` at `delimiter` into at most `capacity` trimmed fields; returns how many fields the
// line has (which may exceed `capacity`: only the first `capacity` are stored).
std::size_t split_fields(std::string_view line, char delimiter, std::string_view* fields,
                         std::size_t capacity);

}  // namespace fibrecell::planner
