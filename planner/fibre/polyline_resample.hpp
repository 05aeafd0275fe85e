#pragma once
// Points along a polyline at most a step apart: what the spacing checks sample, so that a close
// approach between two of its vertices is not missed.

#include <Eigen/Core>

#include <vector>

namespace fibrecell::planner {

// The points of a polyline with points added so that no segment (a closed one's closing segment
// too) is longer than `step` [mm]; a closed polyline's first point is not repeated at the end.
// `vertex`, when given, flags the polyline's own points among them.
std::vector<Eigen::Vector2d> resampled(const std::vector<Eigen::Vector2d>& pts, bool closed,
                                       double step, std::vector<char>* vertex = nullptr);

}  // namespace fibrecell::planner
