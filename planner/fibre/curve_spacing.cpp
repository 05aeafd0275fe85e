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

}  // namespace fibrecell::planner
