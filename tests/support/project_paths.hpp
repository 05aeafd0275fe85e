#pragma once
// Where tests and benchmarks find this checkout: its source tree, the tests' data, the shared
// folder beside it and the build tree. The absolute paths are compiled into project_paths.cpp
// alone, so that every other object is the same in a clone at another path and a compiler cache
// shared by clones hits it (docs/building.md).
//
//   load_job_file(source_path("examples/loop/loop.job.yaml"));
//   run(binary_path("tools/fibrecell") + " plan ...");

#include <string>
#include <string_view>

namespace fibrecell::test {

std::string source_path(std::string_view relative = {});     // <source>/<relative>
std::string test_data_path(std::string_view relative = {});  // <source>/tests/data/<relative>
std::string shared_path(std::string_view relative = {});     // <source>/../shared/<relative>
std::string binary_path(std::string_view relative = {});     // <build>/<relative>

}  // namespace fibrecell::test
