#include "tests/support/project_paths.hpp"

namespace fibrecell::test {

namespace {

std::string join(std::string_view root, std::string_view relative) {
    std::string path(root);
    if (!relative.empty()) path.append("/").append(relative);
    return path;
}

}  // namespace

std::string source_path(std::string_view relative) { return join(FIBRECELL_SOURCE_DIR, relative); }
std::string test_data_path(std::string_view relative) { return join(FIBRECELL_TEST_DATA, relative); }
std::string shared_path(std::string_view relative) { return join(FIBRECELL_SHARED_DIR, relative); }
std::string binary_path(std::string_view relative) { return join(FIBRECELL_BINARY_DIR, relative); }

}  // namespace fibrecell::test
