#include "planner/fibre/segment_grid.hpp"

#include <algorithm>
#include <cmath>

namespace fibrecell::planner {

// Only in the cells the segment passes through, swept along its longer side: a long slanted
// segment in every cell of its bounding box would be visited by every query in that box. A
// segment within a cell of a point passes through one of the 3 x 3 cells around it (where its
// nearest point lies), so the queries still see it.
void SegmentGrid::insert(const TaggedSegment& s) {
    const int id = static_cast<int>(segments_.size());
    segments_.push_back(s);
    const Eigen::Vector2d lo_mm = s.a.cwiseMin(s.b), hi_mm = s.a.cwiseMax(s.b);
    const auto [x0, y0] = cell_of(lo_mm);
    const auto [x1, y1] = cell_of(hi_mm);
    const long lo[2] = {x0, y0}, hi[2] = {x1, y1};
    // Along u, across v: the slope is at most 1, so rounding moves v by about an ulp.
    const Eigen::Vector2d d = s.b - s.a;
    const int u = std::abs(d.x()) >= std::abs(d.y()) ? 0 : 1, v = 1 - u;
    const double slope = hi[u] > lo[u] ? d[v] / d[u] : 0;
    const double margin = 1e-9 * cell_;  // a cell too many, never one too few
    for (long i = lo[u]; i <= hi[u]; ++i) {
        long from = lo[v], to = hi[v];
        if (hi[u] > lo[u]) {  // where the segment crosses this column (or row)
            const double va = s.a[v] + slope * (std::max(lo_mm[u], i * cell_) - s.a[u]);
            const double vb = s.a[v] + slope * (std::min(hi_mm[u], (i + 1) * cell_) - s.a[u]);
            from = std::max(lo[v], std::lround(std::floor((std::min(va, vb) - margin) / cell_)));
            to = std::min(hi[v], std::lround(std::floor((std::max(va, vb) + margin) / cell_)));
        }
        for (long j = from; j <= to; ++j) cells_[u == 0 ? key(i, j) : key(j, i)].push_back(id);
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
