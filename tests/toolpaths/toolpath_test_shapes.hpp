#pragma once
// Hand-built layer outlines and geometric checks shared by the toolpath tests.

#include "planner/layers/layer_mesh.hpp"
#include "planner/toolpaths/toolpath.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace fibrecell::planner::test {

inline Polygon rectangle(double x0, double y0, double x1, double y1) {
    return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};  // counter-clockwise
}

// A clockwise polygon with `n` vertices on a circle: a round hole.
inline Polygon circle_hole(const Eigen::Vector2d& centre, double radius, int n) {
    Polygon loop;
    for (int i = 0; i < n; ++i) {
        const double a = -2 * std::numbers::pi * i / n;
        loop.push_back(centre + radius * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
    return loop;
}

inline LayerOutline rectangle_outline() {
    return {{rectangle(0, 0, 20, 10)}};
}

inline LayerOutline holed_rectangle_outline() {
    return {{rectangle(0, 0, 30, 20), circle_hole({15, 10}, 4, 64)}};
}

// 20 x 20 with the upper-right 12 x 12 quarter cut away.
inline LayerOutline l_shape_outline() {
    return {{{{0, 0}, {20, 0}, {20, 8}, {8, 8}, {8, 20}, {0, 20}}}};
}

inline LayerOutline two_squares_outline() {
    return {{rectangle(0, 0, 10, 10), rectangle(20, 0, 30, 10)}};
}

inline double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                               const Eigen::Vector2d& b) {
    const Eigen::Vector2d ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return (a + t * ab - p).norm();
}

// Distance from p to the nearest outline edge [mm].
inline double distance_to_outline(const Eigen::Vector2d& p, const LayerOutline& outline) {
    double best = std::numeric_limits<double>::infinity();
    for (const Polygon& loop : outline.loops)
        for (std::size_t i = 0; i < loop.size(); ++i)
            best = std::min(best, segment_distance(p, loop[i], loop[(i + 1) % loop.size()]));
    return best;
}

// Even-odd point-in-region test.
inline bool inside(const Eigen::Vector2d& p, const LayerOutline& outline) {
    bool in = false;
    for (const Polygon& loop : outline.loops)
        for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
            const Eigen::Vector2d& a = loop[i];
            const Eigen::Vector2d& b = loop[j];
            if ((a.y() > p.y()) != (b.y() > p.y()) &&
                p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
                in = !in;
        }
    return in;
}

inline std::vector<Toolpath> with_role(const std::vector<Toolpath>& paths, PathRole role) {
    std::vector<Toolpath> out;
    for (const Toolpath& p : paths)
        if (p.role == role) out.push_back(p);
    return out;
}

// The straight pieces of open paths at least `min_length` long: the scan segments of a zigzag.
struct Piece {
    Eigen::Vector2d a, b;
};
inline std::vector<Piece> long_pieces(const std::vector<Toolpath>& paths, double min_length) {
    std::vector<Piece> pieces;
    for (const Toolpath& path : paths)
        for (std::size_t i = 1; i < path.points.size(); ++i)
            if ((path.points[i] - path.points[i - 1]).norm() >= min_length)
                pieces.push_back({path.points[i - 1], path.points[i]});
    return pieces;
}

// Direction of a piece in [0, 180) degrees.
inline double direction_deg(const Piece& piece) {
    const Eigen::Vector2d d = piece.b - piece.a;
    double a = std::atan2(d.y(), d.x()) * 180 / std::numbers::pi;
    if (a < 0) a += 180;
    if (a >= 180 - 1e-6) a -= 180;
    return a;
}

}  // namespace fibrecell::planner::test
