#include "planner/fibre/laid_fibre.hpp"

#include "planner/fibre/polyline_resample.hpp"
#include "planner/progress.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

namespace fibrecell::planner {
namespace {

// The points of `s` flagged as vertices, and the first and last: the same line, without the
// samples that only lie on it.
std::vector<Eigen::Vector2d> vertices_of(const std::vector<Eigen::Vector2d>& points,
                                         const std::vector<char>& vertex) {
    std::vector<Eigen::Vector2d> out;
    for (std::size_t k = 0; k < points.size(); ++k)
        if (vertex[k] || k == 0 || k + 1 == points.size()) out.push_back(points[k]);
    return out;
}

double length_of(const std::vector<Eigen::Vector2d>& pts) {
    double l = 0;
    for (std::size_t k = 1; k < pts.size(); ++k) l += (pts[k] - pts[k - 1]).norm();
    return l;
}

}  // namespace

LaidFibre::LaidFibre(double w, double tolerance_mm) : w_(w), keep_(w - tolerance_mm), grid_(w) {}

bool LaidFibre::near(const SegmentGrid& grid, const Eigen::Vector2d& p) const {
    const double keep2 = keep_ * keep_;
    return grid.any_around(p, [&](const TaggedSegment& s) {
        return point_segment_distance_squared(p, s.a, s.b) < keep2;
    });
}

void LaidFibre::commit(const LaidPiece& piece) {
    grid_.insert_polyline(piece.points, piece.closed, 0);
}

bool LaidFibre::keeps_itself(const std::vector<Eigen::Vector2d>& loop) const {
    const std::size_t n = loop.size();
    std::vector<double> at(n, 0);
    for (std::size_t k = 1; k < n; ++k) at[k] = at[k - 1] + (loop[k] - loop[k - 1]).norm();
    const double length = at[n - 1] + (loop.front() - loop.back()).norm();
    SegmentGrid own(w_);
    for (std::size_t k = 0; k < n; ++k)
        own.insert({loop[k], loop[(k + 1) % n], static_cast<int>(k)});
    for (std::size_t k = 0; k < n; ++k) {
        bool crowded = false;
        own.around(loop[k], [&](const TaggedSegment& s) {
            const double apart = std::abs(at[static_cast<std::size_t>(s.tag)] - at[k]);
            // Any of the segment (its start, or W/4 on) more than 4W away round the loop, the
            // shorter way.
            if (std::min(apart, length - apart) > 4 * w_ - w_ / 4)
                crowded = crowded || point_segment_distance(loop[k], s.a, s.b) < keep_;
        });
        if (crowded) return false;
    }
    return true;
}

std::vector<LaidPiece> LaidFibre::lay(const std::vector<Eigen::Vector2d>& points, bool closed,
                                      double min_piece_mm) {
    const bool loop = closed && points.size() > 2;
    std::vector<char> vertex;
    std::vector<Eigen::Vector2d> pts = resampled(points, loop, w_ / 4, &vertex);
    if (pts.size() < 2) return {};
    if (!loop) return lay_open(pts, vertex, min_piece_mm);
    const auto blocked = std::find_if(pts.begin(), pts.end(),
                                      [&](const Eigen::Vector2d& p) { return near(grid_, p); });
    if (blocked == pts.end() && keeps_itself(pts)) {
        const double length = length_of(pts) + (pts.front() - pts.back()).norm();
        if (length < min_piece_mm) {
            ++dropped_short_;
            dropped_short_mm_ += length;
            return {};
        }
        LaidPiece whole{points, true};
        commit(whole);
        return {whole};
    }
    // Cut open: walked from a point that crowds what is laid (or from its start when only the
    // loop crowds itself), once round.
    const auto first = blocked == pts.end() ? 0 : blocked - pts.begin();
    std::rotate(pts.begin(), pts.begin() + first, pts.end());
    std::rotate(vertex.begin(), vertex.begin() + first, vertex.end());
    pts.push_back(pts.front());
    vertex.push_back(vertex.front());
    return lay_open(pts, vertex, min_piece_mm);
}

std::vector<LaidPiece> LaidFibre::lay_open(const std::vector<Eigen::Vector2d>& pts,
                                           const std::vector<char>& vertex, double min_piece_mm) {
    struct Pending {
        Eigen::Vector2d a, b;
        double along;  // of a: once it is 4W behind, so is part of the segment
    };
    std::deque<Pending> pending;  // this piece's segments not yet reaching 4W behind
    SegmentGrid own(w_);          // this piece's segments reaching 4W behind or more
    std::vector<LaidPiece> out;
    std::vector<Eigen::Vector2d> piece;
    std::vector<char> piece_vertex;
    const auto finish = [&] {
        if (piece.size() > 1) {
            const double length = length_of(piece);
            if (length >= min_piece_mm) {
                out.push_back({vertices_of(piece, piece_vertex), false});
                commit(out.back());
            } else {
                ++dropped_short_;
                dropped_short_mm_ += length;
            }
        }
        piece.clear();
        piece_vertex.clear();
        pending.clear();
        own = SegmentGrid(w_);
    };
    double along = 0;
    for (std::size_t k = 0; k < pts.size(); ++k) {
        cancellation_point();
        if (k > 0) along += (pts[k] - pts[k - 1]).norm();
        // A W/4 early: a point between this sample and the last, 4W past a segment's start,
        // is then measured against it at both samples (else it could come 3% nearer than W).
        while (!pending.empty() && pending.front().along <= along - 4 * w_ + w_ / 4) {
            own.insert({pending.front().a, pending.front().b, 0});
            pending.pop_front();
        }
        if (near(grid_, pts[k]) || near(own, pts[k])) {
            finish();
            continue;
        }
        if (!piece.empty())
            pending.push_back({piece.back(), pts[k], along - (pts[k] - piece.back()).norm()});
        piece.push_back(pts[k]);
        piece_vertex.push_back(vertex[k]);
    }
    finish();
    return out;
}

}  // namespace fibrecell::planner
