#pragma once
// A uniform grid of tagged 2D segments for "what is near this point" queries: each query only
// looks at the 3 x 3 cells around the point, never at all segments.

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>
#include <vector>

namespace fibrecell::planner {

struct TaggedSegment {
    Eigen::Vector2d a, b;  // [mm]
    int tag = 0;           // what the segment belongs to (a curve level, a path)
};

// Distance [mm] from p to the segment ab. Inline: the planner's nearness queries call it for
// every segment they visit.
inline double point_segment_distance_squared(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                                             const Eigen::Vector2d& b) {
    const Eigen::Vector2d ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    return (a + t * ab - p).squaredNorm();
}
inline double point_segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                                     const Eigen::Vector2d& b) {
    return std::sqrt(point_segment_distance_squared(p, a, b));
}

// Whether segments ab and cd cross at a point inside both (touching and overlapping are found
// by the ends' distances instead).
inline bool segments_cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                           const Eigen::Vector2d& c, const Eigen::Vector2d& d) {
    const auto side = [](const Eigen::Vector2d& o, const Eigen::Vector2d& p,
                         const Eigen::Vector2d& q) {
        return (p.x() - o.x()) * (q.y() - o.y()) - (p.y() - o.y()) * (q.x() - o.x());
    };
    return side(a, b, c) * side(a, b, d) < 0 && side(c, d, a) * side(c, d, b) < 0;
}

// Distance [mm] between segments ab and cd: 0 where they cross, else the nearest of their ends
// to the other segment (two segments that do not cross come closest at an end of one of them).
inline double segment_distance(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                               const Eigen::Vector2d& c, const Eigen::Vector2d& d) {
    if (segments_cross(a, b, c, d)) return 0;
    return std::min(std::min(point_segment_distance(a, c, d), point_segment_distance(b, c, d)),
                    std::min(point_segment_distance(c, a, b), point_segment_distance(d, a, b)));
}

class SegmentGrid {
  public:
    // cell_mm: the largest distance a query needs to see; nearer segments are always visited.
    explicit SegmentGrid(double cell_mm) : cell_(cell_mm) {}

    void insert(const TaggedSegment& s);
    // Every segment of a polyline (and its closing segment when closed), with one tag.
    void insert_polyline(const std::vector<Eigen::Vector2d>& points, bool closed, int tag);

    // The id-th segment inserted.
    const TaggedSegment& segment(std::size_t id) const { return segments_[id]; }

    // Calls visit(segment) for the segments in the 3 x 3 cells around p (a segment may be
    // visited more than once).
    template <class Visit>
    void around(const Eigen::Vector2d& p, Visit visit) const {
        any_around(p, [&](const TaggedSegment& s) {
            visit(s);
            return false;
        });
    }

    // Whether near(segment) holds for any segment in the 3 x 3 cells around p: stops at the
    // first that does.
    template <class Near>
    bool any_around(const Eigen::Vector2d& p, Near near) const {
        const auto [cx, cy] = cell_of(p);
        for (long x = cx - 1; x <= cx + 1; ++x)
            for (long y = cy - 1; y <= cy + 1; ++y)
                if (auto it = cells_.find(key(x, y)); it != cells_.end())
                    for (int id : it->second)
                        if (near(segments_[id])) return true;
        return false;
    }

    // Calls visit(segment) for the segments in the cells around the box [lo, hi] (one cell
    // beyond it on every side: everything within a cell of any point in the box).
    template <class Visit>
    void around_box(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, Visit visit) const {
        const auto [x0, y0] = cell_of(lo);
        const auto [x1, y1] = cell_of(hi);
        for (long x = x0 - 1; x <= x1 + 1; ++x)
            for (long y = y0 - 1; y <= y1 + 1; ++y)
                if (auto it = cells_.find(key(x, y)); it != cells_.end())
                    for (int id : it->second) visit(segments_[id]);
    }

  private:
    std::pair<long, long> cell_of(const Eigen::Vector2d& p) const {
        return {std::lround(std::floor(p.x() / cell_)), std::lround(std::floor(p.y() / cell_))};
    }
    static long long key(long x, long y) {
        return (static_cast<long long>(x) << 32) ^ (static_cast<long long>(y) & 0xffffffffLL);
    }

    double cell_;
    std::vector<TaggedSegment> segments_;
    std::unordered_map<long long, std::vector<int>> cells_;
};

}  // namespace fibrecell::planner
