#pragma once
// What this build is, for `--version`, server.info and the job history: a bug report and a
// printed part can name the build that made them (cmake/write_build_info.cmake writes them).

#include <string>

namespace fibrecell::config {

const char* build_version();  // the project's version ("0.1.0")
const char* build_commit();   // `git describe --always --dirty` of the sources, or "unknown"

// "0.1.0 (commit 524331a1b2c3)"
inline std::string build_name() {
    return std::string(build_version()) + " (commit " + build_commit() + ")";
}

}  // namespace fibrecell::config
