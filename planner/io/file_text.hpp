#pragma once
// Whole-file input: the readers parse from memory, which is what makes them fast.

#include <string>

namespace fibrecell::planner {

// The bytes of the file at `path`. Throws InputError naming the file when it is missing, is a
// directory or cannot be read.
std::string read_file_text(const std::string& path);

}  // namespace fibrecell::planner
