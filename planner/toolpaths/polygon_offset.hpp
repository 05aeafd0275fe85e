#pragma once
// Polygon offsets and island splitting on top of Clipper 6.4, the one place that knows Clipper's
// integer coordinates (1 unit = 1e-5 mm: a 300 mm bed spans 3e7 units, far inside Clipper's
// 64-bit range, and rounding stays below 1e-5 mm).

#include "planner/layers/layer_mesh.hpp"

#include <vector>

namespace fibrecell::planner {

struct OffsetOptions {
    double arc_tolerance_mm = 0.002;  // largest gap between a round join's chords and its arc
};

// Offsets a region by delta_mm with round joins: > 0 grows it (outer loops move out, holes
// shrink), < 0 shrinks it. `loops` [mm] is read even-odd, so nesting decides outer or hole and
// orientation does not matter. Returns the offset region's loops [mm], outer loops counter-
// clockwise, holes clockwise; empty when the region vanishes. Every returned vertex lies at
// |delta_mm| from the input boundary (up to 1e-5 mm); chords of round joins may cut up to
// arc_tolerance_mm closer. Throws std::invalid_argument on a loop with fewer than 3 points or a
// non-finite coordinate.
std::vector<Polygon> offset_region(const std::vector<Polygon>& loops, double delta_mm,
                                   const OffsetOptions& options = {});

// Splits a region (read even-odd) into islands: each an outer loop (counter-clockwise) followed by
// its holes (clockwise). An island inside a hole of another is its own island. Throws as above.
std::vector<std::vector<Polygon>> split_islands(const std::vector<Polygon>& loops);

}  // namespace fibrecell::planner
