#pragma once
// Boundary rings too short to lay on their own (paper Section 4.4): a ring round a small pin
// hole is shorter than the distance from the cutter to the nozzle, so it is opened and laid as
// the continuation of a neighbouring stress path instead of being dropped.

#include "planner/fibre/isocurves.hpp"
#include "planner/layers/layer_mesh.hpp"

#include <vector>

namespace fibrecell::planner {

struct RingAttachOptions {
    double spacing_mm = 1.0;           // W
    double cutter_distance_mm = 42.0;  // rings shorter than this are joined
    double reach_mm = 0;               // farthest path end from the ring (3W when 0)
};

// paths: a piece's stress paths after the connection; rings: its boundary rings (closed, or
// arcs along a partly selected loop); part: where any fibre may lie (the outline inset W/2).
// Each ring shorter than the cutter distance is appended to the end of a path within reach, a
// closed ring opened where the link meets it and stopped 1.5W short of coming round, when the
// joined fibre is long enough to cut, keeps W from itself (points more than 4W apart along it), its link keeps W from
// every other curve and lies in `part`. Joined rings are removed from `rings` and their count
// returned (and, when `joined_at` is given, the first point of each, as it was, appended); the
// rest are left for the caller's length check.
std::size_t attach_short_rings(std::vector<Polyline>& paths, std::vector<Polyline>& rings,
                               const std::vector<Polygon>& part, const RingAttachOptions& options,
                               std::vector<Eigen::Vector2d>* joined_at = nullptr);

}  // namespace fibrecell::planner
