#pragma once
// Stripes along the stress of one layer piece, for the field-dense strategy: a periodic phase
// whose level lines follow a line field at a fixed spacing (Knoeppel, Crane, Pinkall, Schroeder,
// "Stripe patterns on surfaces", ACM TOG 34(4), 2015; used for continuous-fibre toolpaths by
// Zhang et al., Composites Part B 295, 2025). Unlike one scalar field (the field strategy), the
// phase may branch: where the stress lines converge or diverge a stripe ends (a singular
// triangle) instead of the spacing drifting, so the stripes keep their spacing over the piece.

#include "planner/fibre/isocurves.hpp"
#include "planner/layers/layer_mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace fibrecell::planner {

struct StripeOptions {
    double spacing_mm = 1.0;  // distance between neighbouring stripes where the field lets them
    int iterations = 20;      // inverse-iteration solves for the smallest eigenvector
};

struct StripePattern {
    std::vector<Polyline> stripes;     // the level lines (phase = 0 mod 2 pi), chained
    std::size_t singular_triangles = 0;  // where the phase branches: no stripe crosses them
};

// direction_f: per triangle of `piece`, the direction the stripes should run (its sign and length
// do not matter; a zero vector leaves the triangle's neighbours to decide).
StripePattern stripe_pattern(const LayerMesh& piece, const std::vector<Eigen::Vector2d>& direction_f,
                             const StripeOptions& options = {});

}  // namespace fibrecell::planner
