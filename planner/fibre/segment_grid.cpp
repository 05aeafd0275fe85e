#include "planner/fibre/segment_grid.hpp"

#include <algorithm>
#include <cmath>

namespace fibrecell::planner {

// Only in the cells the segment passes through, column by column: a long slanted segment in
// every cell of its bounding box would be visited by every query in that box. A segment within
// a cell of a point passes through one of the 3 x 3 cells around it (where its nearest point
// lies), so the queries still see it.
void SegmentGrid::insert(const TaggedSegment& s) {
    const auto [x0, y0] = cell_of(s.a.cwiseMin(s.b));
    const auto [x1, y1] = cell_of(s.a.cwiseMax(s.b));
    const int id = static_cast<int>(segments_.size());
    segments_.push_back(s);
    const double x_lo = std::min(s.a.x(), s.b.x()), x_hi = std::max(s.a.x(), s.b.x());
    const double slope = x1 > x0 ? (s.b.y() - s.a.y()) / (s.b.x() - s.a.x()) : 0;
    const double margin = 1e-9 * cell_;  // rounding: a cell too many, never one too few
    for (long x = x0; x <= x1; ++x) {
        long from = y0, to = y1;
        if (x1 > x0) {  // the segment's y where it crosses this column
            const double ya = s.a.y() + slope * (std::max(x_lo, x * cell_) - s.a.x());
            const double yb = s.a.y() + slope * (std::min(x_hi, (x + 1) * cell_) - s.a.x());
            from = std::max(y0, std::lround(std::floor((std::min(ya, yb) - margin) / cell_)));
            to = std::min(y1, std::lround(std::floor((std::max(ya, yb) + margin) / cell_)));
        }
        for (long y = from; y <= to; ++y) cells_[key(x, y)].push_back(id);
    }
}

void SegmentGrid::insert_polyline(const std::vector<Eigen::Vector2d>& points, bool closed,
                                  int tag) {
    const std::size_t n = points.size();
    for (std::size_t i = 0; i + 1 < n; ++i) insert({points[i], points[i + 1], tag});
    if (closed && n > 2) insert({points[n - 1], points[0], tag});
    if (n == 1) insert({points[0], points[0], tag});
}

}  // namespace fibrecell::planner
