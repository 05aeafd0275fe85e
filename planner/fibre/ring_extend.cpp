#include "planner/fibre/ring_extend.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

namespace fibrecell::planner {
namespace {

// The loop and vertex `p` is (to a hair), or {-1, -1}.
std::pair<int, int> vertex_of(const std::vector<Polygon>& loops, const Eigen::Vector2d& p) {
    for (std::size_t l = 0; l < loops.size(); ++l)
        for (std::size_t k = 0; k < loops[l].size(); ++k)
            if ((loops[l][k] - p).squaredNorm() < 1e-12)
                return {static_cast<int>(l), static_cast<int>(k)};
    return {-1, -1};
}

double loop_length(const Polygon& loop) {
    double l = 0;
    for (std::size_t k = 0; k < loop.size(); ++k)
        l += (loop[(k + 1) % loop.size()] - loop[k]).norm();
    return l;
}

// Appends the points of a-b after a, b included, no two more than `step` apart.
template <class Push>
void densify_to(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double step, Push push) {
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
    for (int i = 1; i <= n; ++i) push(a + (b - a) * (static_cast<double>(i) / n));
}

}  // namespace

std::size_t extend_short_rings(std::vector<Polyline>& rings, const std::vector<Polygon>& loops,
                               const RingExtendOptions& options) {
    std::size_t grown = 0;
    for (Polyline& ring : rings) {
        if (ring.closed || ring.points.size() < 2) continue;
        double length = polyline_length(ring);
        if (length >= options.min_length_mm) continue;
        const auto [loop_front, front] = vertex_of(loops, ring.points.front());
        const auto [loop_back, back] = vertex_of(loops, ring.points.back());
        if (loop_front < 0 || loop_front != loop_back) continue;
        const Polygon& loop = loops[static_cast<std::size_t>(loop_front)];
        if (loop_length(loop) < options.min_length_mm) continue;
        const int n = static_cast<int>(loop.size());
        std::deque<Eigen::Vector2d> points(ring.points.begin(), ring.points.end());
        // The loop's vertices not yet in the ring lie after `back` and before `front`: grow into
        // them from both ends, one vertex at a time, the shorter end first.
        int ahead = (back + 1) % n, behind = (front - 1 + n) % n;
        int free = (front - back - 1 + 2 * n) % n;  // loop vertices not in the ring
        double grown_ahead = 0, grown_behind = 0;
        while (length < options.min_length_mm && free > 0) {
            if (grown_ahead <= grown_behind) {
                const Eigen::Vector2d from = points.back();
                const double before = length;
                densify_to(from, loop[static_cast<std::size_t>(ahead)], options.step_mm,
                           [&](const Eigen::Vector2d& q) {
                               length += (q - points.back()).norm();
                               points.push_back(q);
                           });
                grown_ahead += length - before;
                ahead = (ahead + 1) % n;
            } else {
                const Eigen::Vector2d from = points.front();
                const double before = length;
                densify_to(from, loop[static_cast<std::size_t>(behind)], options.step_mm,
                           [&](const Eigen::Vector2d& q) {
                               length += (q - points.front()).norm();
                               points.push_front(q);
                           });
                grown_behind += length - before;
                behind = (behind - 1 + n) % n;
            }
            --free;
        }
        ring.points.assign(points.begin(), points.end());
        ++grown;
    }
    return grown;
}

}  // namespace fibrecell::planner
