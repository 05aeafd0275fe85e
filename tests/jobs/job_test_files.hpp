#pragma once
// What the job tests share: a fresh folder per test, files read back whole, and the small bar they
// plan (50 x 6 x 0.8 mm, pulled along x at 30 MPa: one PLA and one CCF layer of straight fibres).

#include "planner/io/vtk_writer.hpp"
#include "planner/mesh/structured_mesh.hpp"
#include "tests/support/plan_inputs.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fibrecell::test {

namespace fs = std::filesystem;

inline std::string read_file(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// <tmp>/<prefix>-<current test's name>, empty.
inline fs::path fresh_test_dir(const std::string& prefix) {
    const fs::path dir = fs::temp_directory_path() /
                         (prefix + "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// The bar's mesh at `vtk`; without `stressed`, the same mesh with no stress (cannot be planned).
inline void write_tension_bar(const fs::path& vtk, bool stressed = true) {
    const auto mesh = planner::structured_tet_mesh({.size = {50, 6, 0.8}, .cells = {25, 3, 1}});
    std::vector<planner::StressTensor> stress(mesh.tet_count(), planner::StressTensor::Zero());
    for (auto& s : stress) s(0, 0) = 30.0;
    fibrecell::test::write_vtk_file(vtk, mesh, stressed ? planner::FieldArrays{.stress = &stress}
                                                          : planner::FieldArrays{});
}

}  // namespace fibrecell::test
