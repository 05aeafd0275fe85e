#include "planner/fibre/curve_spacing.hpp"

#include "planner/fibre/segment_grid.hpp"

#include <algorithm>
#include <cmath>

namespace fibrecell::planner {

double min_neighbour_distance(const std::vector<Polyline>& curves, double cap) {
    SegmentGrid grid(cap);
    for (const auto& c : curves) grid.insert_polyline(c.points, c.closed, c.level);
    double best = cap;
    for (const auto& c : curves)
        for (const auto& p : c.points)
            grid.around(p, [&](const TaggedSegment& s) {
                if (std::abs(s.tag - c.level) == 1)
                    best = std::min(best, point_segment_distance(p, s.a, s.b));
            });
    return best;
}

double min_distance_between_paths(const std::vector<std::vector<Eigen::Vector2d>>& paths,
                                  const std::vector<char>& closed, double cap) {
    SegmentGrid grid(cap);
    for (std::size_t i = 0; i < paths.size(); ++i)
        grid.insert_polyline(paths[i], closed[i], static_cast<int>(i));
    double best = cap;
    for (std::size_t i = 0; i < paths.size(); ++i)
        for (const auto& p : paths[i])
            grid.around(p, [&](const TaggedSegment& s) {
                if (s.tag != static_cast<int>(i))
                    best = std::min(best, point_segment_distance(p, s.a, s.b));
            });
    return best;
}

double min_fibre_spacing(const std::vector<std::vector<Eigen::Vector2d>>& paths,
                         const std::vector<char>& closed, double along_mm, double cap) {
    // Segments tagged by their index in `segs`, which knows the path and where along it they lie.
    struct Piece {
        int path;
        double from_mm, to_mm;  // along the path
    };
    std::vector<Piece> segs;
    std::vector<std::vector<double>> at(paths.size());  // along-path position of each vertex
    std::vector<double> length(paths.size(), 0);
    SegmentGrid grid(cap);
    for (std::size_t i = 0; i < paths.size(); ++i) {
        const auto& pts = paths[i];
        double s = 0;
        for (std::size_t k = 0; k < pts.size(); ++k) {
            if (k > 0) s += (pts[k] - pts[k - 1]).norm();
            at[i].push_back(s);
        }
        const bool loop = closed[i] && pts.size() > 2;
        const std::size_t count = loop ? pts.size() : (pts.empty() ? 0 : pts.size() - 1);
        for (std::size_t k = 0; k < count; ++k) {
            const Eigen::Vector2d& a = pts[k];
            const Eigen::Vector2d& b = pts[(k + 1) % pts.size()];
            const double from = at[i][k];
            grid.insert({a, b, static_cast<int>(segs.size())});
            segs.push_back({static_cast<int>(i), from, from + (b - a).norm()});
        }
        length[i] = loop ? s + (pts.front() - pts.back()).norm() : s;
    }
    // How far along its path the nearest point of a piece is from position `s`.
    const auto apart = [&](const Piece& piece, double s) {
        double d = s < piece.from_mm ? piece.from_mm - s : s > piece.to_mm ? s - piece.to_mm : 0.0;
        const std::size_t i = static_cast<std::size_t>(piece.path);
        if (closed[i]) {
            const double around = std::min(std::abs(length[i] - s + piece.from_mm),
                                           std::abs(length[i] - piece.to_mm + s));
            d = std::min(d, around);
        }
        return d;
    };
    double best = cap;
    for (std::size_t i = 0; i < paths.size(); ++i)
        for (std::size_t k = 0; k < paths[i].size(); ++k) {
            const Eigen::Vector2d& p = paths[i][k];
            grid.around(p, [&](const TaggedSegment& seg) {
                const Piece& piece = segs[static_cast<std::size_t>(seg.tag)];
                if (piece.path == static_cast<int>(i) && !(apart(piece, at[i][k]) > along_mm)) return;
                best = std::min(best, point_segment_distance(p, seg.a, seg.b));
            });
        }
    return best;
}

double fibre_spacing_mm(const std::vector<Toolpath>& paths, double w) {
    if (paths.empty()) return 0;
    std::vector<std::vector<Eigen::Vector2d>> points;
    std::vector<char> closed;
    for (const Toolpath& p : paths) {
        points.push_back(p.points);
        closed.push_back(p.closed);
    }
    return min_fibre_spacing(points, closed, 4 * w, 3 * w);
}

}  // namespace fibrecell::planner
