#pragma once
// What the job tests share besides their folder (tests/support/temp_dir.hpp): the small bar they
// plan (50 x 6 x 0.8 mm, pulled along x at 30 MPa: one PLA and one CCF layer of straight fibres).

#include "planner/io/vtk_writer.hpp"
#include "planner/mesh/structured_mesh.hpp"
#include "tests/support/plan_inputs.hpp"
#include "tests/support/temp_dir.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace fibrecell::test {

namespace fs = std::filesystem;

// The bar's mesh at `vtk`; without `stressed`, the same mesh with no stress (cannot be planned).
inline void write_tension_bar(const fs::path& vtk, bool stressed = true) {
    const auto mesh = planner::structured_tet_mesh({.size = {50, 6, 0.8}, .cells = {25, 3, 1}});
    std::vector<planner::StressTensor> stress(mesh.tet_count(), planner::StressTensor::Zero());
    for (auto& s : stress) s(0, 0) = 30.0;
    fibrecell::test::write_vtk_file(vtk, mesh, stressed ? planner::FieldArrays{.stress = &stress}
                                                          : planner::FieldArrays{});
}

}  // namespace fibrecell::test
