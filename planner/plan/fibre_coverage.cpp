#include "planner/plan/fibre_coverage.hpp"

#include "planner/toolpaths/path_order.hpp"
#include "planner/toolpaths/polygon_offset.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace fibrecell::planner {
namespace {

// Rows of the scan per ribbon width: the covered area is summed row by row (the midpoint rule
// across the rows, exact along them), which is exact for edges along the rows and within a few
// per mille elsewhere; a union of the ribbons' polygons took 30-90 ms a layer on the Loop.
constexpr double rows_per_w = 16;

using Interval = std::pair<double, double>;  // [from, to] in x [mm]

// The x-interval where the row at height y crosses the convex polygon `corners`, if it does.
template <std::size_t N>
bool row_through(const std::array<Eigen::Vector2d, N>& corners, double y, Interval& out) {
    double lo = INFINITY, hi = -INFINITY;
    for (std::size_t k = 0; k < N; ++k) {
        const Eigen::Vector2d& a = corners[k];
        const Eigen::Vector2d& b = corners[(k + 1) % N];
        if ((a.y() > y) == (b.y() > y)) continue;
        const double x = a.x() + (y - a.y()) / (b.y() - a.y()) * (b.x() - a.x());
        lo = std::min(lo, x);
        hi = std::max(hi, x);
    }
    if (!(lo < hi)) return false;
    out = {lo, hi};
    return true;
}

// Merges intervals (sorted in place) and returns the merged ones.
std::vector<Interval> merged(std::vector<Interval>& intervals) {
    std::sort(intervals.begin(), intervals.end());
    std::vector<Interval> out;
    for (const Interval& i : intervals) {
        if (!out.empty() && i.first <= out.back().second)
            out.back().second = std::max(out.back().second, i.second);
        else
            out.push_back(i);
    }
    return out;
}

// Length of the intersection of two sets of disjoint sorted intervals.
double overlap(const std::vector<Interval>& a, const std::vector<Interval>& b) {
    double sum = 0;
    std::size_t i = 0, j = 0;
    while (i < a.size() && j < b.size()) {
        sum += std::max(0.0, std::min(a[i].second, b[j].second) - std::max(a[i].first, b[j].first));
        (a[i].second < b[j].second ? i : j) += 1;
    }
    return sum;
}

class RowScan {
  public:
    RowScan(double y0, double pitch, std::size_t rows) : y0_(y0), pitch_(pitch), rows_(rows) {}

    double y(std::size_t row) const { return y0_ + (static_cast<double>(row) + 0.5) * pitch_; }
    std::size_t rows() const { return rows_; }
    // The rows whose heights lie in [lo, hi].
    std::pair<std::size_t, std::size_t> rows_between(double lo, double hi) const {
        const double first = std::ceil((lo - y0_) / pitch_ - 0.5);
        const double last = std::floor((hi - y0_) / pitch_ - 0.5);
        const auto clamp = [&](double r) {
            return static_cast<std::size_t>(std::clamp(r, 0.0, static_cast<double>(rows_)));
        };
        return {clamp(first), clamp(last + 1)};
    }

  private:
    double y0_, pitch_;
    std::size_t rows_;
};

// Per row, where the region (loops read even-odd) lies.
std::vector<std::vector<Interval>> region_rows(const std::vector<Polygon>& region, const RowScan& scan) {
    std::vector<std::vector<double>> xs(scan.rows());
    for (const Polygon& loop : region)
        for (std::size_t k = 0; k < loop.size(); ++k) {
            const Eigen::Vector2d& a = loop[k];
            const Eigen::Vector2d& b = loop[(k + 1) % loop.size()];
            const auto [from, to] = scan.rows_between(std::min(a.y(), b.y()), std::max(a.y(), b.y()));
            for (std::size_t r = from; r < to; ++r) {
                const double y = scan.y(r);
                if ((a.y() > y) == (b.y() > y)) continue;
                xs[r].push_back(a.x() + (y - a.y()) / (b.y() - a.y()) * (b.x() - a.x()));
            }
        }
    std::vector<std::vector<Interval>> rows(scan.rows());
    for (std::size_t r = 0; r < rows.size(); ++r) {
        std::sort(xs[r].begin(), xs[r].end());
        for (std::size_t k = 0; k + 1 < xs[r].size(); k += 2) rows[r].push_back({xs[r][k], xs[r][k + 1]});
    }
    return rows;
}

// Per row, the x-intervals of the W-wide ribbons along the paths: a rectangle per segment, cut
// square at an open path's ends, and a disc at each joint between two segments (a round join).
std::vector<std::vector<Interval>> ribbon_rows(const std::vector<Toolpath>& paths, double w,
                                               const RowScan& scan) {
    const double r = w / 2;
    std::vector<std::vector<Interval>> rows(scan.rows());
    const auto add_segment = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
        const Eigen::Vector2d d = b - a;
        const double length = d.norm();
        if (!(length > 0)) return;
        const Eigen::Vector2d n = Eigen::Vector2d(-d.y(), d.x()) * (r / length);
        const std::array<Eigen::Vector2d, 4> quad{a + n, b + n, b - n, a - n};
        const double lo = std::min(a.y(), b.y()) - std::abs(n.y());
        const double hi = std::max(a.y(), b.y()) + std::abs(n.y());
        const auto [from, to] = scan.rows_between(lo, hi);
        Interval i;
        for (std::size_t row = from; row < to; ++row)
            if (row_through(quad, scan.y(row), i)) rows[row].push_back(i);
    };
    const auto add_joint = [&](const Eigen::Vector2d& c) {
        const auto [from, to] = scan.rows_between(c.y() - r, c.y() + r);
        for (std::size_t row = from; row < to; ++row) {
            const double dy = scan.y(row) - c.y();
            const double half = std::sqrt(std::max(0.0, r * r - dy * dy));
            if (half > 0) rows[row].push_back({c.x() - half, c.x() + half});
        }
    };
    for (const Toolpath& p : paths) {
        const std::size_t n = p.points.size();
        if (n < 2) continue;
        const bool loop = p.closed && n > 2;
        for (std::size_t k = 0; k + 1 < n; ++k) add_segment(p.points[k], p.points[k + 1]);
        if (loop) add_segment(p.points[n - 1], p.points[0]);
        for (std::size_t k = loop ? 0 : 1; k < (loop ? n : n - 1); ++k) add_joint(p.points[k]);
    }
    return rows;
}

}  // namespace

FibreCoverage& FibreCoverage::operator+=(const FibreCoverage& o) {
    if (o.ribbon_mm > 0) ribbon_mm = o.ribbon_mm;
    region_mm2 += o.region_mm2;
    fibre_mm += o.fibre_mm;
    covered_mm2 += o.covered_mm2;
    return *this;
}

FibreCoverage fibre_coverage(const LayerOutline& outline, const std::vector<Toolpath>& paths,
                             double w) {
    if (!(w > 0) || !std::isfinite(w))
        throw std::invalid_argument("fibre coverage: the ribbon width must be positive");
    FibreCoverage c{.ribbon_mm = w};
    for (const Toolpath& p : paths) c.fibre_mm += path_length(p);
    if (outline.loops.empty()) return c;
    const std::vector<Polygon> region = offset_region(outline.loops, -w / 2);
    c.region_mm2 = region_area(region);
    if (c.region_mm2 <= 0 || c.fibre_mm <= 0) return c;

    double y_lo = INFINITY, y_hi = -INFINITY;
    for (const Polygon& loop : region)
        for (const Eigen::Vector2d& p : loop) {
            y_lo = std::min(y_lo, p.y());
            y_hi = std::max(y_hi, p.y());
        }
    const double pitch = w / rows_per_w;
    const RowScan scan(y_lo, pitch, static_cast<std::size_t>(std::ceil((y_hi - y_lo) / pitch)));
    const auto inside = region_rows(region, scan);
    auto ribbons = ribbon_rows(paths, w, scan);
    double covered = 0;
    for (std::size_t row = 0; row < scan.rows(); ++row)
        covered += overlap(inside[row], merged(ribbons[row])) * pitch;
    c.covered_mm2 = std::min(covered, c.region_mm2);
    return c;
}

}  // namespace fibrecell::planner
