#include "planner/plan/boundary_fibre_stats.hpp"

#include "planner/fibre/polyline_resample.hpp"
#include "planner/fibre/segment_grid.hpp"
#include "planner/toolpaths/path_order.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fibrecell::planner {
namespace {

constexpr double sample_mm = 0.5;

// The distance from p to the nearest segment of `grid` within its cell size (infinity beyond).
double nearest(const SegmentGrid& grid, const Eigen::Vector2d& p) {
    double best = std::numeric_limits<double>::infinity();
    grid.around(p, [&](const TaggedSegment& s) {
        best = std::min(best, point_segment_distance(p, s.a, s.b));
    });
    return best;
}

}  // namespace

BoundaryFibreStats& BoundaryFibreStats::operator+=(const BoundaryFibreStats& o) {
    edge_mm += o.edge_mm;
    covered_mm += o.covered_mm;
    rings += o.rings;
    rings_joined += o.rings_joined;
    joins += o.joins;
    ring_mm += o.ring_mm;
    ring_distance_mm.insert(ring_distance_mm.end(), o.ring_distance_mm.begin(),
                            o.ring_distance_mm.end());
    return *this;
}

double BoundaryFibreStats::ring_distance_quantile(double q) const {
    if (ring_distance_mm.empty()) return 0.0;
    std::vector<double> sorted = ring_distance_mm;
    const auto k = static_cast<std::size_t>(
        std::lround(std::clamp(q, 0.0, 1.0) * static_cast<double>(sorted.size() - 1)));
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(k), sorted.end());
    return sorted[k];
}

BoundaryFibreStats boundary_fibre_stats(const LayerMesh& layer,
                                        const std::vector<std::array<int, 2>>& edges,
                                        const std::vector<Toolpath>& paths, double spacing_mm,
                                        const FibreJoins& joins) {
    BoundaryFibreStats out;
    if (edges.empty()) return out;
    const double reach = 1.5 * spacing_mm + 0.2;  // a ring's place, with the tolerance

    SegmentGrid fibre(reach);
    for (std::size_t i = 0; i < paths.size(); ++i)
        fibre.insert_polyline(paths[i].points, paths[i].closed, static_cast<int>(i));
    SegmentGrid boundary(3 * spacing_mm);
    for (const auto& [a, b] : edges) {
        const Eigen::Vector2d p = layer.vertices[a], q = layer.vertices[b];
        boundary.insert({p, q, 0});
        // The edge in pieces of at most sample_mm, each judged at its middle.
        const double len = (q - p).norm();
        const int pieces = std::max(1, static_cast<int>(std::ceil(len / sample_mm)));
        for (int k = 0; k < pieces; ++k) {
            const Eigen::Vector2d mid = p + (q - p) * ((k + 0.5) / pieces);
            out.edge_mm += len / pieces;
            if (nearest(fibre, mid) <= reach) out.covered_mm += len / pieces;
        }
    }
    for (const Toolpath& path : paths) {
        if (path.role != PathRole::fibre_boundary || path.points.size() < 2) continue;
        // The ring's points along this boundary: an arc run on past the boundary's ends
        // (extend_short_rings) lies along other edges there, and another boundary's ring
        // nowhere near.
        std::vector<double> d;
        for (const Eigen::Vector2d& p : resampled(path.points, path.closed, sample_mm))
            if (const double near = nearest(boundary, p); near <= 2 * spacing_mm) d.push_back(near);
        if (d.empty()) continue;
        ++out.rings;
        out.ring_mm += path_length(path);
        out.ring_distance_mm.insert(out.ring_distance_mm.end(), d.begin(), d.end());
    }
    for (const Eigen::Vector2d& p : joins.rings_joined)
        out.rings_joined += nearest(boundary, p) <= 2 * spacing_mm;
    for (const Eigen::Vector2d& p : joins.links)
        out.joins += nearest(boundary, p) <= 3 * spacing_mm;
    return out;
}

}  // namespace fibrecell::planner
