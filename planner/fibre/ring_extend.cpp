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

// The points from a (left out) to b, no two more than `step` apart.
std::vector<Eigen::Vector2d> way_to(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                    double step) {
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
    std::vector<Eigen::Vector2d> out;
    for (int i = 1; i <= n; ++i) out.push_back(a + (b - a) * (static_cast<double>(i) / n));
    return out;
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
            const bool at_back = grown_ahead <= grown_behind;
            int& next = at_back ? ahead : behind;
            Eigen::Vector2d last = at_back ? points.back() : points.front();
            double added = 0;
            for (const Eigen::Vector2d& q :
                 way_to(last, loop[static_cast<std::size_t>(next)], options.step_mm)) {
                added += (q - last).norm();
                last = q;
                if (at_back)
                    points.push_back(q);
                else
                    points.push_front(q);
            }
            length += added;
            (at_back ? grown_ahead : grown_behind) += added;
            next = (next + (at_back ? 1 : n - 1)) % n;
            --free;
        }
        ring.points.assign(points.begin(), points.end());
        ++grown;
    }
    return grown;
}

}  // namespace fibrecell::planner
