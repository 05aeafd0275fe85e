#pragma once
// Benchmark parts: Loop-like plates of a chosen size with the load case the benchmarks solve.

#include "planner/fea/linear_elastic.hpp"
#include "planner/mesh/boundary.hpp"
#include "planner/mesh/structured_mesh.hpp"

#include <algorithm>
#include <cmath>

namespace fibrecell::bench {

using namespace fibrecell::planner;

// A Loop-like plate (140 x 100 x 10 mm, central opening, two pin holes) meshed with about
// `target_tets` structured tets.
inline TetMesh loop_like_plate(int target_tets) {
    auto keep = [](const Eigen::Vector3d& c) {
        const double ox = std::max(0.0, std::abs(c.x() - 70.0) - 15.0);  // 70 x 40 stadium
        const bool in_opening = std::hypot(ox, c.y() - 50.0) < 20.0;
        const bool in_pin = std::hypot(c.x() - 15.0, c.y() - 50.0) < 6.0 ||
                            std::hypot(c.x() - 125.0, c.y() - 50.0) < 6.0;
        return !in_opening && !in_pin;
    };
    // Guess the cell size from the plate volume, then correct it once by the measured count.
    auto mesh_with = [&](double h) {
        StructuredMeshOptions o;
        o.size = {140, 100, 10};
        o.cells = {static_cast<int>(std::lround(140 / h)), static_cast<int>(std::lround(100 / h)),
                   std::max(1, static_cast<int>(std::lround(10 / h)))};
        o.keep_cell = keep;
        return structured_tet_mesh(o);
    };
    const double h = std::cbrt(6.0 * 140.0 * 100.0 * 10.0 / target_tets);
    const double ratio = static_cast<double>(mesh_with(h).tet_count()) / target_tets;
    return mesh_with(h * std::cbrt(ratio));
}

// Clamped at x = 0, pulled with 2 kN at x = 140.
inline LoadCase end_load(const TetMesh& mesh) {
    const auto boundary = boundary_triangles(mesh);
    LoadCase lc;
    FixedRegion fixed{"x0", {}};
    ForceRegion pull{"x140", {}, Eigen::Vector3d(2000, 0, 0)};
    for (const auto& t : boundary) {
        bool at0 = true, at140 = true;
        for (int v : t.v) {
            at0 = at0 && mesh.vertices[v].x() < 1e-9;
            at140 = at140 && mesh.vertices[v].x() > 140 - 1e-9;
        }
        if (at0) fixed.vertices.insert(fixed.vertices.end(), t.v.begin(), t.v.end());
        if (at140) pull.triangles.push_back(t);
    }
    lc.supports.push_back(fixed);
    lc.loads.push_back(pull);
    return lc;
}

}  // namespace fibrecell::bench
