#pragma once
// Writing plan files so that a reader (the service, a browser) never sees a half-written one.

#include <string>

namespace fibrecell::planner {

// Writes `text` to `path` through `path.tmp` and a rename. Throws std::runtime_error naming the
// path when the file cannot be written.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace fibrecell::planner
