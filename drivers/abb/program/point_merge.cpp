#include "drivers/abb/program/point_merge.hpp"

#include <algorithm>

namespace fibrecell::drivers::abb {

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                           const Eigen::Vector2d& b) {
    const Eigen::Vector2d ab = b - a;
    const double len2 = ab.squaredNorm();
    if (len2 <= 0) return (p - a).norm();
    const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
    return (p - (a + t * ab)).norm();
}

std::vector<std::size_t> merge_points(std::span<const Eigen::Vector2d> points,
                                      std::span<const std::size_t> fixed,
                                      const PointMergeOptions& options) {
    std::vector<std::size_t> kept;
    if (points.empty()) return kept;
    const std::size_t last = points.size() - 1;
    // Stops: the first point, every fixed index, the last point.
    std::vector<char> stop(points.size(), 0), keep(points.size(), 0);
    stop[0] = stop[last] = 1;
    for (const std::size_t f : fixed)
        if (f < points.size()) stop[f] = 1;

    // Douglas-Peucker between consecutive stops: a point is kept when it lies farther than the
    // tolerance from the segment that would replace it.
    std::vector<std::pair<std::size_t, std::size_t>> todo;
    for (std::size_t a = 0, b = 1; b <= last; ++b)
        if (stop[b]) {
            todo.emplace_back(a, b);
            a = b;
        }
    while (!todo.empty()) {
        const auto [a, b] = todo.back();
        todo.pop_back();
        keep[a] = keep[b] = 1;
        if (b - a < 2) continue;
        std::size_t worst = a;
        double worst_d = options.chord_tolerance_mm;
        for (std::size_t i = a + 1; i < b; ++i) {
            const double d = distance_to_segment(points[i], points[a], points[b]);
            if (d > worst_d) {
                worst_d = d;
                worst = i;
            }
        }
        if (worst == a) continue;
        todo.emplace_back(a, worst);
        todo.emplace_back(worst, b);
    }

    // Minimum segment length: drop kept points closer than that to the previous one; a short
    // piece into a stop drops the previous (unfixed) point instead.
    kept.push_back(0);
    for (std::size_t i = 1; i <= last; ++i) {
        if (!keep[i]) continue;
        const bool short_piece = (points[i] - points[kept.back()]).norm() < options.min_segment_mm;
        if (!stop[i]) {
            if (!short_piece) kept.push_back(i);
            continue;
        }
        if (short_piece && !stop[kept.back()]) kept.pop_back();
        kept.push_back(i);
    }
    return kept;
}

}  // namespace fibrecell::drivers::abb
