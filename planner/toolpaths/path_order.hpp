#pragma once
// Print order of a layer's paths: nearest-first, to keep travel moves short.

#include "planner/toolpaths/toolpath.hpp"

#include <vector>

namespace fibrecell::planner {

// Where the nozzle starts and ends a path [mm] (a closed path ends where it starts).
Eigen::Vector2d path_start(const Toolpath& path);
Eigen::Vector2d path_end(const Toolpath& path);

// Printed length [mm], the closing segment of a closed path included.
double path_length(const Toolpath& path);

// Greedy nearest-neighbour order from `start_mm`: the next path is the one that can be entered
// nearest to the current position. A closed path is entered at its nearest vertex (rotated to
// start there), an open path at its nearer end (reversed if that is its last point). Returns the
// same paths in print order. O(#paths * #points).
std::vector<Toolpath> order_nearest(std::vector<Toolpath> paths, const Eigen::Vector2d& start_mm);

}  // namespace fibrecell::planner
