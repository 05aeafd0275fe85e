#include "planner/fibre/curve_spacing.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace fibrecell::planner {
namespace {

struct SegmentRef {
    Eigen::Vector2d a, b;
    int level;
};

double point_segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                              const Eigen::Vector2d& b) {
    const Eigen::Vector2d ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    return (a + t * ab - p).norm();
}

class SegmentGrid {
  public:
    explicit SegmentGrid(double cell) : cell_(cell) {}

    void insert(const SegmentRef& s) {
        const auto [x0, y0] = cell_of(s.a.cwiseMin(s.b));
        const auto [x1, y1] = cell_of(s.a.cwiseMax(s.b));
        const int id = static_cast<int>(segments_.size());
        segments_.push_back(s);
        for (long x = x0; x <= x1; ++x)
            for (long y = y0; y <= y1; ++y) cells_[key(x, y)].push_back(id);
    }

    // Calls visit(segment) for the segments in the 3 x 3 cells around p.
    template <class F>
    void around(const Eigen::Vector2d& p, F visit) const {
        const auto [cx, cy] = cell_of(p);
        for (long x = cx - 1; x <= cx + 1; ++x)
            for (long y = cy - 1; y <= cy + 1; ++y)
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
    std::vector<SegmentRef> segments_;
    std::unordered_map<long long, std::vector<int>> cells_;
};

}  // namespace

double min_neighbour_distance(const std::vector<Polyline>& curves, double cap) {
    SegmentGrid grid(cap);
    for (const auto& c : curves) {
        const std::size_t n = c.points.size();
        for (std::size_t i = 0; i + 1 < n; ++i)
            grid.insert({c.points[i], c.points[i + 1], c.level});
        if (c.closed && n > 2) grid.insert({c.points[n - 1], c.points[0], c.level});
    }
    double best = cap;
    for (const auto& c : curves) {
        for (const auto& p : c.points) {
            grid.around(p, [&](const SegmentRef& s) {
                if (std::abs(s.level - c.level) == 1)
                    best = std::min(best, point_segment_distance(p, s.a, s.b));
            });
        }
    }
    return best;
}

}  // namespace fibrecell::planner
