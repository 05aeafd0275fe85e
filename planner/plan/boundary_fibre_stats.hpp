#pragma once
// How the boundary-conformal fibre of a layer lies along one selected boundary (report.json
// `fibre.boundaries`), measured on the finished paths against the layer's true outline edges:
// how much of the boundary has fibre alongside, and where its rings sit.

#include "planner/layers/layer_mesh.hpp"
#include "planner/toolpaths/toolpath.hpp"

#include <Eigen/Core>

#include <array>
#include <span>
#include <vector>

namespace fibrecell::planner {

// Sums over layers; combine them with +=.
struct BoundaryFibreStats {
    double edge_mm = 0;     // the boundary's outline length in the layers
    double covered_mm = 0;  // of it, with fibre within 1.5W + 0.2 mm (a ring or a joined one)
    int rings = 0;          // fibre-boundary paths following this boundary (within 2W of it)
    int rings_joined = 0;   // its rings too short to cut, laid on from a stress path
    int joins = 0;          // links of the connection made within 3W of it
    double ring_mm = 0;
    // Ring points every 0.5 mm within 2W of the boundary: their distance to it.
    std::vector<double> ring_distance_mm;

    BoundaryFibreStats& operator+=(const BoundaryFibreStats& o);
    double coverage() const { return edge_mm > 0 ? covered_mm / edge_mm : 0.0; }
    // The q-quantile (0..1) of ring_distance_mm; 0 without rings.
    double ring_distance_quantile(double q) const;
};

// Where the connection joined fibre (FibreLayer::join_points, joined_ring_points).
struct FibreJoins {
    std::span<const Eigen::Vector2d> links;         // a point of each link
    std::span<const Eigen::Vector2d> rings_joined;  // a point of each ring laid on a stress path
};

// edges: the boundary's outline edges of `layer` (vertex pairs, selected_outline_edges); paths:
// the layer's fibre paths; spacing_mm: W. A fibre-boundary path counts as this boundary's ring
// when its median point lies within 2W of the boundary, a joined ring when its point does, a link
// when its point lies within 3W.
BoundaryFibreStats boundary_fibre_stats(const LayerMesh& layer,
                                        const std::vector<std::array<int, 2>>& edges,
                                        const std::vector<Toolpath>& paths, double spacing_mm,
                                        const FibreJoins& joins = {});

}  // namespace fibrecell::planner
