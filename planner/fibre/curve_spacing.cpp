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

namespace {

// A piece of a path (no longer than the cap): where it lies along the path, and the path's fine
// points that lie on it.
struct Piece {
    int path;
    double from_mm, to_mm;
    std::size_t first_point, end_point;  // [first, end) into the path's fine points
};

// Distance from p (at `s` along a path of length `length`) to the part of a piece of the same
// path that lies more than along_mm from s along it (around a closed path, the shorter way).
double far_part(const Eigen::Vector2d& p, double s, const Piece& piece, const TaggedSegment& seg,
                double along_mm, double length, bool closed) {
    const double big = std::numeric_limits<double>::infinity();
    const std::pair<double, double> wanted[2] = {
        closed ? std::pair{s + along_mm, s + length - along_mm} : std::pair{s + along_mm, big},
        closed ? std::pair{s - length + along_mm, s - along_mm} : std::pair{-big, s - along_mm}};
    const double span = piece.to_mm - piece.from_mm;
    double best = big;
    for (const auto& [lo, hi] : wanted) {
        const double a = std::max(lo, piece.from_mm), b = std::min(hi, piece.to_mm);
        if (!(a < b) || span <= 0) continue;
        const Eigen::Vector2d d = seg.b - seg.a;
        best = std::min(best, point_segment_distance(p, seg.a + d * ((a - piece.from_mm) / span),
                                                     seg.a + d * ((b - piece.from_mm) / span)));
    }
    return best;
}

// A path's points every `step` along it, and how far along it each lies.
struct FinePoints {
    std::vector<Eigen::Vector2d> points;
    std::vector<double> at;
    double length = 0;
};

FinePoints fine_points(const std::vector<Eigen::Vector2d>& path, bool closed, double step) {
    FinePoints out{resampled(path, closed, step), {}, 0};
    const auto& pts = out.points;
    double s = 0;
    for (std::size_t k = 0; k < pts.size(); ++k) {
        if (k > 0) s += (pts[k] - pts[k - 1]).norm();
        out.at.push_back(s);
    }
    out.length = closed && pts.size() > 2 ? s + (pts.front() - pts.back()).norm() : s;
    return out;
}

}  // namespace

double min_fibre_spacing(const std::vector<std::vector<Eigen::Vector2d>>& given,
                         const std::vector<char>& closed, double along_mm, double cap) {
    // The paths in pieces no longer than the cap, each spanning a grid cell or two, and their
    // points every along/32 (W/8 at 4W), which find a close pair within one path to W/16.
    std::vector<FinePoints> fine;
    fine.reserve(given.size());
    std::vector<Piece> pieces;
    SegmentGrid grid(cap);  // the pieces, tagged by their index in `pieces`
    for (std::size_t i = 0; i < given.size(); ++i) {
        fine.push_back(fine_points(given[i], closed[i], along_mm / 32));
        const FinePoints& f = fine.back();
        const std::vector<Eigen::Vector2d> coarse = resampled(given[i], closed[i], cap);
        const bool loop = closed[i] && coarse.size() > 2;
        // A lone point is a piece of no length.
        const std::size_t count =
            loop ? coarse.size() : (coarse.size() == 1 ? 1 : (coarse.empty() ? 0 : coarse.size() - 1));
        double from = 0;
        std::size_t point = 0;
        for (std::size_t k = 0; k < count; ++k) {
            const Eigen::Vector2d& a = coarse[k];
            const Eigen::Vector2d& b = coarse[(k + 1) % coarse.size()];
            const double to = from + (b - a).norm();
            const std::size_t first = point;
            while (point < f.points.size() && (k + 1 == count || f.at[point] < to)) ++point;
            grid.insert({a, b, static_cast<int>(pieces.size())});
            pieces.push_back({static_cast<int>(i), from, to, first, point});
            from = to;
        }
    }

    // Each piece against the pieces within a cell of it, once per pair and direction. Between
    // paths the distance of the two pieces is exact, and it is what points every W/8 on them
    // would find: two polylines that do not cross come closest at a vertex of one of them. Within
    // a path only the part of the other piece more than along_mm away along it counts, measured
    // from each of this piece's points; the pieces' own distance bounds that from below, so a
    // pair that cannot beat the nearest found so far is passed over.
    std::vector<std::size_t> seen(pieces.size(), pieces.size());
    double best = cap;
    for (std::size_t pi = 0; pi < pieces.size(); ++pi) {
        cancellation_point();
        const Piece& piece = pieces[pi];
        const TaggedSegment& ps = grid.segment(pi);
        const FinePoints& f = fine[static_cast<std::size_t>(piece.path)];
        grid.around_box(ps.a.cwiseMin(ps.b), ps.a.cwiseMax(ps.b), [&](const TaggedSegment& qs) {
            const std::size_t qi = static_cast<std::size_t>(qs.tag);
            if (qi == pi || seen[qi] == pi) return;  // a piece has no far part of itself
            seen[qi] = pi;
            const Piece& other = pieces[qi];
            const bool same_path = other.path == piece.path;
            // Pieces of one path nearer along it than along_mm at their farthest: nothing far.
            if (same_path && std::max(other.to_mm - piece.from_mm, piece.to_mm - other.from_mm) <=
                                 along_mm)
                return;
            const double d = segment_distance(ps.a, ps.b, qs.a, qs.b);
            if (d >= best) return;
            if (!same_path) {
                best = d;
                return;
            }
            const bool loop = closed[static_cast<std::size_t>(piece.path)] != 0;
            for (std::size_t k = piece.first_point; k < piece.end_point; ++k)
                best = std::min(best, far_part(f.points[k], f.at[k], other, qs, along_mm,
                                               f.length, loop));
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
