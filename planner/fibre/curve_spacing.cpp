#include "planner/fibre/curve_spacing.hpp"

#include "planner/fibre/polyline_resample.hpp"
#include "planner/fibre/segment_grid.hpp"
#include "planner/progress.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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
        for (const auto& p : paths[i]) {
            cancellation_point();  // a layer's paths can hold a million points
            grid.around(p, [&](const TaggedSegment& s) {
                if (s.tag != static_cast<int>(i))
                    best = std::min(best, point_segment_distance(p, s.a, s.b));
            });
        }
    return best;
}

double min_fibre_spacing(const std::vector<std::vector<Eigen::Vector2d>>& given,
                         const std::vector<char>& closed, double along_mm, double cap) {
    // Points every along/32 (W/8 at 4W) find a close pair within one path to W/16. The segments
    // they are measured to need no such density (the distance to a segment is exact), only to
    // span at most a grid cell or two: pieces no longer than the cap.
    std::vector<std::vector<Eigen::Vector2d>> paths;
    paths.reserve(given.size());
    for (std::size_t i = 0; i < given.size(); ++i)
        paths.push_back(resampled(given[i], closed[i], along_mm / 32));
    // Segments tagged by their index in `segs`, which knows the path and where along it they lie.
    struct Piece {
        int path;
        double from_mm, to_mm;  // along the path
    };
    std::vector<Piece> segs;
    std::vector<std::vector<double>> at(paths.size());  // along-path position of each point
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
        length[i] = loop ? s + (pts.front() - pts.back()).norm() : s;

        const std::vector<Eigen::Vector2d> coarse = resampled(given[i], closed[i], cap);
        const bool coarse_loop = closed[i] && coarse.size() > 2;
        const std::size_t count =
            coarse_loop ? coarse.size() : (coarse.empty() ? 0 : coarse.size() - 1);
        double from = 0;
        for (std::size_t k = 0; k < count; ++k) {
            const Eigen::Vector2d& a = coarse[k];
            const Eigen::Vector2d& b = coarse[(k + 1) % coarse.size()];
            const double to = from + (b - a).norm();
            grid.insert({a, b, static_cast<int>(segs.size())});
            segs.push_back({static_cast<int>(i), from, to});
            from = to;
        }
    }
    // Distance from p (at `s` along path i) to the part of a segment of the same path that lies
    // more than along_mm from s along the path (around a closed path, the shorter way).
    const auto far_part = [&](const Eigen::Vector2d& p, double s, const Piece& piece,
                              const TaggedSegment& seg) {
        const std::size_t i = static_cast<std::size_t>(piece.path);
        const double big = std::numeric_limits<double>::infinity();
        const double l = length[i];
        const std::pair<double, double> wanted[2] = {
            closed[i] ? std::pair{s + along_mm, s + l - along_mm} : std::pair{s + along_mm, big},
            closed[i] ? std::pair{s - l + along_mm, s - along_mm} : std::pair{-big, s - along_mm}};
        const double span = piece.to_mm - piece.from_mm;
        double best = big;
        for (const auto& [lo, hi] : wanted) {
            const double a = std::max(lo, piece.from_mm), b = std::min(hi, piece.to_mm);
            if (!(a < b) || span <= 0) continue;
            const Eigen::Vector2d d = seg.b - seg.a;
            best =
                std::min(best, point_segment_distance(p, seg.a + d * ((a - piece.from_mm) / span),
                                                      seg.a + d * ((b - piece.from_mm) / span)));
        }
        return best;
    };
    double best = cap;
    for (std::size_t i = 0; i < paths.size(); ++i)
        for (std::size_t k = 0; k < paths[i].size(); ++k) {
            cancellation_point();
            const Eigen::Vector2d& p = paths[i][k];
            grid.around(p, [&](const TaggedSegment& seg) {
                const Piece& piece = segs[static_cast<std::size_t>(seg.tag)];
                best = std::min(best, piece.path == static_cast<int>(i)
                                          ? far_part(p, at[i][k], piece, seg)
                                          : point_segment_distance(p, seg.a, seg.b));
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
    // Near W first: the grid's cell is the distance it sees, and a small cell visits far fewer
    // segments. Anything found below that cap is the true minimum; only a layer whose paths are
    // all farther apart needs the wide search.
    const double near = min_fibre_spacing(points, closed, 4 * w, 1.25 * w);
    return near < 1.25 * w ? near : min_fibre_spacing(points, closed, 4 * w, 3 * w);
}

}  // namespace fibrecell::planner
