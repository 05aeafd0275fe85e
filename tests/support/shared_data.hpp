#pragma once
// The project's shared folder beside the repository (shared_path(), project_paths.hpp)
// holds the reference FEA data sets (third-party, BSD-3-Clause), which the repository does not
// carry. A clone without that folder must still test cleanly: a test that needs a data set skips
// with the reason instead of failing (README.md, "The shared folder").
//
//   TEST(Reference, Reads) {
//       FIBRECELL_SKIP_WITHOUT_REFERENCE_FEA("bunnyhead");
//       read_volume_model(reference_fea_stem("bunnyhead") + ".tet", ...);
//   }
//
// Benchmarks use the functions alone (they have no GTEST_SKIP).

#include "tests/support/project_paths.hpp"

#include <filesystem>
#include <string>

namespace fibrecell::test {

// <shared>/data/reference-fea, normalised so that messages show a plain path.
inline std::filesystem::path reference_fea_dir() {
    return std::filesystem::path(shared_path("data/reference-fea")).lexically_normal();
}

// The files of data set `name` are this stem plus ".tet", "_stress.txt" and "_selection.txt".
inline std::string reference_fea_stem(const std::string& name,
                                      const std::filesystem::path& dir = reference_fea_dir()) {
    return (dir / name / name).string();
}

// Why data set `name` cannot be read (the first missing file and where the data comes from), or
// empty when all its files are there.
inline std::string reference_fea_missing(const std::string& name,
                                         const std::filesystem::path& dir = reference_fea_dir()) {
    const std::string stem = reference_fea_stem(name, dir);
    for (const char* suffix : {".tet", "_stress.txt", "_selection.txt"}) {
        std::error_code ec;
        if (std::filesystem::is_regular_file(stem + suffix, ec)) continue;
        return "reference FEA data not found at " + stem + suffix +
               ": it ships in the project's shared folder beside the repository "
               "(shared/data/reference-fea, BSD-3-Clause), not in the repository itself";
    }
    return {};
}

}  // namespace fibrecell::test

// Skips the calling test (GTEST_SKIP returns from it) when data set `name` is missing.
#define FIBRECELL_SKIP_WITHOUT_REFERENCE_FEA(name)                                             \
    if (const std::string fibrecell_missing_ = ::fibrecell::test::reference_fea_missing(name); \
        !fibrecell_missing_.empty())                                                           \
    GTEST_SKIP() << fibrecell_missing_
