#pragma once
// Boundary rings too short to cut that no stress path could take on (ring_attach): a small
// selected patch of the outline (a handle, a clamp face) gives an arc at 1.5W shorter than the
// cutter distance. Rather than drop it, the arc runs on along the d = 1.5W loop it lies on, past
// the selected boundary's ends, until the cutter can cut it: the selected boundary keeps its
// conformal fibre, at the price of some ring along its neighbours.

#include "planner/fibre/isocurves.hpp"
#include "planner/layers/layer_mesh.hpp"

#include <vector>

namespace fibrecell::planner {

struct RingExtendOptions {
    double min_length_mm = 42.0;  // the cutter distance: what a ring must reach
    double step_mm = 1.0;         // no added segment longer than this (W)
};

// rings: open arcs and closed rings, as fibre_region gives them (an arc's ends are vertices of
// one of `loops`, its points in the loop's order); loops: the d = 1.5W loops. Each open arc
// shorter than min_length_mm grows at both ends in turn along its loop until it is long enough
// (a loop too short for that as a whole is left as it is). Returns how many arcs grew.
std::size_t extend_short_rings(std::vector<Polyline>& rings, const std::vector<Polygon>& loops,
                               const RingExtendOptions& options = {});

}  // namespace fibrecell::planner
