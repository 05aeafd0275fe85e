#pragma once
// Distances between isocurves of neighbouring levels, through a uniform grid of segments: each
// curve vertex only looks at segments in the cells around it, never at all pairs.

#include "planner/fibre/isocurves.hpp"
#include "planner/toolpaths/toolpath.hpp"

#include <vector>

namespace fibrecell::planner {

// Minimal distance [mm] between curves whose levels differ by one. Distances of `cap` or more
// are not searched: the result is then `cap`. For polylines that do not cross, the closest pair
// always involves a vertex of one of them, so vertex-to-segment distances are exact.
double min_neighbour_distance(const std::vector<Polyline>& curves, double cap);

// Minimal distance [mm] between points of different paths (vertex to segment), capped the same
// way.
double min_distance_between_paths(const std::vector<std::vector<Eigen::Vector2d>>& paths,
                                  const std::vector<char>& closed, double cap);

// The spacing a finished fibre layer actually has: the minimal distance [mm] between points of
// different paths, and between points of one path more than `along_mm` apart along it (a
// hairpin, a cusp, a join that comes back; around a closed path the shorter way), capped.
// Between paths exact (0 where two cross); within a path found to within along_mm/64 on points
// every along_mm/32.
double min_fibre_spacing(const std::vector<std::vector<Eigen::Vector2d>>& paths,
                         const std::vector<char>& closed, double along_mm, double cap);

// A fibre layer's spacing as the plan reports it (fibre.min_spacing_mm), for either strategy:
// min_fibre_spacing over its paths with pieces of one path 4W apart along it, capped at 3W (no
// two points nearer than that); 0 for a layer without paths.
double fibre_spacing_mm(const std::vector<Toolpath>& paths, double w);

}  // namespace fibrecell::planner
