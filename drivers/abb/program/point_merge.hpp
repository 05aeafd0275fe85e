#pragma once
// Thinning a toolpath polyline for the controller: dense, nearly collinear points cost program
// lines and overload the path planner (event 50078; docs/robot-program.md, "Merging") without
// changing the path.

#include <Eigen/Core>

#include <cstddef>
#include <span>
#include <vector>

namespace fibrecell::drivers::abb {

struct PointMergeOptions {
    // A dropped point stays at most this far from the segment that replaces it [mm].
    double chord_tolerance_mm = 0.02;
    // Segments shorter than this are merged with the next one even if that leaves the chord
    // tolerance (the controller cannot follow dense short segments at speed) [mm]; 0 = off.
    double min_segment_mm = 0.3;
};

// Indices of the points of `points` [mm] to keep, ascending, always including the first, the
// last and every index in `fixed` (event positions: never moved, never dropped). Between fixed
// points, Douglas-Peucker: every dropped point lies within the chord tolerance of the segment
// that replaces it. Then points closer than min_segment_mm to the previous kept point are
// dropped too, unless fixed; a short piece into a fixed point drops the previous (unfixed) kept
// point instead. Only the minimum-length step may leave the chord tolerance.
std::vector<std::size_t> merge_points(std::span<const Eigen::Vector2d> points,
                                      std::span<const std::size_t> fixed,
                                      const PointMergeOptions& options = {});

// Distance of `p` from the segment a-b [mm] (from a when a == b).
double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                           const Eigen::Vector2d& b);

}  // namespace fibrecell::drivers::abb
