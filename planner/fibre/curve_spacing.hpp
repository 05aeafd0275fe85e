#pragma once
// Distances between isocurves of neighbouring levels, through a uniform grid of segments: each
// curve vertex only looks at segments in the cells around it, never at all pairs.

#include "planner/fibre/isocurves.hpp"

#include <vector>

namespace fibrecell::planner {

// Minimal distance [mm] between curves whose levels differ by one. Distances of `cap` or more
// are not searched: the result is then `cap`. For polylines that do not cross, the closest pair
// always involves a vertex of one of them, so vertex-to-segment distances are exact.
double min_neighbour_distance(const std::vector<Polyline>& curves, double cap);

// Minimal distance [mm] between points of different paths (vertex to segment), capped the same
// way: the spacing a finished fibre layer actually has.
double min_distance_between_paths(const std::vector<std::vector<Eigen::Vector2d>>& paths,
                                  const std::vector<char>& closed, double cap);

}  // namespace fibrecell::planner
