#include "planner/fibre/segment_grid.hpp"

#include <algorithm>

namespace fibrecell::planner {

void SegmentGrid::insert(const TaggedSegment& s) {
    const auto [x0, y0] = cell_of(s.a.cwiseMin(s.b));
    const auto [x1, y1] = cell_of(s.a.cwiseMax(s.b));
    const int id = static_cast<int>(segments_.size());
    segments_.push_back(s);
    for (long x = x0; x <= x1; ++x)
        for (long y = y0; y <= y1; ++y) cells_[key(x, y)].push_back(id);
}

void SegmentGrid::insert_polyline(const std::vector<Eigen::Vector2d>& points, bool closed,
                                  int tag) {
    const std::size_t n = points.size();
    for (std::size_t i = 0; i + 1 < n; ++i) insert({points[i], points[i + 1], tag});
    if (closed && n > 2) insert({points[n - 1], points[0], tag});
    if (n == 1) insert({points[0], points[0], tag});
}

}  // namespace fibrecell::planner
