#include "planner/fibre/gap_fill.hpp"

#include "planner/fibre/segment_grid.hpp"
#include "planner/layers/outline.hpp"
#include "planner/layers/triangle_locator.hpp"
#include "planner/toolpaths/path_order.hpp"
#include "planner/toolpaths/polygon_offset.hpp"
#include "planner/toolpaths/zigzag_fill.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

namespace fibrecell::planner {
namespace {

// The band round the laid fibre, a bare region's edge, is drawn round the paths thinned to
// thin_mm (Douglas-Peucker) with round joins to arc_mm: the stripes' and rings' dense vertices
// made its union most of the layer's planning time. It is widened by what both may take off
// (a thinned line strays thin_mm, a chord lies 2.25 arc tolerances inside its arc) and a hair,
// so that a fill line on its edge still passes LaidFibre's W.
constexpr double thin_mm = 0.01;
constexpr double arc_mm = 0.005;
constexpr double band_margin_mm = thin_mm + 2.25 * arc_mm + 0.002;

// Douglas-Peucker: the points of `pts` that keep every dropped one within `tolerance` of the
// thinned line.
std::vector<Eigen::Vector2d> thinned(const std::vector<Eigen::Vector2d>& pts, double tolerance) {
    if (pts.size() < 3) return pts;
    std::vector<char> keep(pts.size(), 0);
    keep.front() = keep.back() = 1;
    std::vector<std::pair<std::size_t, std::size_t>> spans{{0, pts.size() - 1}};
    while (!spans.empty()) {
        const auto [a, b] = spans.back();
        spans.pop_back();
        double worst = tolerance;
        std::size_t at = a;
        for (std::size_t k = a + 1; k < b; ++k) {
            const double d = point_segment_distance(pts[k], pts[a], pts[b]);
            if (d > worst) worst = d, at = k;
        }
        if (at == a) continue;
        keep[at] = 1;
        spans.push_back({a, at});
        spans.push_back({at, b});
    }
    std::vector<Eigen::Vector2d> out;
    for (std::size_t k = 0; k < pts.size(); ++k)
        if (keep[k]) out.push_back(pts[k]);
    return out;
}

struct Box {
    Eigen::Vector2d lo, hi;
    bool holds(const Eigen::Vector2d& p) const {
        return p.x() >= lo.x() && p.y() >= lo.y() && p.x() <= hi.x() && p.y() <= hi.y();
    }
};

Box bounds(const std::vector<Polygon>& island) {
    Box b{island.front().front(), island.front().front()};
    for (const Eigen::Vector2d& p : island.front()) {
        b.lo = b.lo.cwiseMin(p);
        b.hi = b.hi.cwiseMax(p);
    }
    return b;
}

// A line direction from doubled angles summed with weights: its angle [deg] from +x.
struct LineMean {
    Eigen::Vector2d doubled = Eigen::Vector2d::Zero();
    void add(const Eigen::Vector2d& v, double weight) {
        const double angle = std::atan2(v.y(), v.x());
        doubled += weight * Eigen::Vector2d(std::cos(2 * angle), std::sin(2 * angle));
    }
    bool empty() const { return doubled.squaredNorm() == 0; }
    double degrees() const { return std::atan2(doubled.y(), doubled.x()) / 2 * 180.0 / std::numbers::pi; }
};

// The line field's mean over the triangles whose centroid lies in the island, each weighted by
// its area and stress (a direction and its opposite agree); nullopt when none has one.
std::optional<double> stress_direction_deg(const std::vector<Polygon>& island,
                                           const LayerMesh& layer, const LayerField& field,
                                           const std::vector<Eigen::Vector2d>& centroid) {
    const Box box = bounds(island);
    LineMean mean;
    for (std::size_t f = 0; f < layer.triangles.size(); ++f) {
        if (!box.holds(centroid[f]) || !inside_region(island, centroid[f])) continue;
        if (field.v_f[f].squaredNorm() == 0) continue;
        const auto& t = layer.triangles[f];
        const Eigen::Vector2d e1 = layer.vertices[t[1]] - layer.vertices[t[0]];
        const Eigen::Vector2d e2 = layer.vertices[t[2]] - layer.vertices[t[0]];
        const double area = 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
        mean.add(field.v_f[f], area * (std::max(field.sigma_f[f], 0.0) + 1e-6));
    }
    if (mean.empty()) return std::nullopt;
    return mean.degrees();
}

// The island's long axis: its outer loop's edges, weighted by length (a thin band runs along it).
double long_axis_deg(const std::vector<Polygon>& island) {
    const Polygon& loop = island.front();
    LineMean mean;
    for (std::size_t i = 0; i < loop.size(); ++i) {
        const Eigen::Vector2d e = loop[(i + 1) % loop.size()] - loop[i];
        mean.add(e, e.norm());
    }
    return mean.degrees();
}

// How much of a candidate fill runs along the stress: the length of its paths that are at least
// the cutter distance long (nothing shorter can be laid), each segment counted by |cos| of its
// angle to the field's direction where it lies (0 where the field has none).
double aligned_mm(const std::vector<Toolpath>& paths, const TriangleLocator& where,
                  const LayerField& field, double cutter_distance_mm) {
    double total = 0;
    for (const Toolpath& p : paths) {
        if (path_length(p) < cutter_distance_mm) continue;
        std::vector<Eigen::Vector2d> pts = p.points;
        if (p.closed && !pts.empty()) pts.push_back(pts.front());
        for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
            const Eigen::Vector2d d = pts[k + 1] - pts[k];
            const double l = d.norm();
            if (l == 0) continue;
            // The field where it lies, every 2 mm or so: a long zigzag line crosses a turning field.
            const int n = std::max(1, static_cast<int>(std::ceil(l / 2.0)));
            for (int j = 0; j < n; ++j) {
                const int f = where.locate(pts[k] + d * ((j + 0.5) / n));
                if (f < 0) continue;
                const Eigen::Vector2d v = field.v_f[static_cast<std::size_t>(f)];
                if (v.squaredNorm() > 0) total += std::abs(d.dot(v)) / v.norm() / n;
            }
        }
    }
    return total;
}

// Rings round an island from its edge inwards, W apart: the outer one runs W from the paths
// beside it, so along the stress where they do (a wedge between two stripes gets a hairpin along
// both of them), and round a pin or along the outline where the island meets them.
std::vector<Toolpath> island_rings(const std::vector<Polygon>& island, double w) {
    std::vector<Toolpath> rings;
    for (int k = 0;; ++k) {
        const std::vector<Polygon> loops = k == 0 ? island : offset_region(island, -k * w);
        if (loops.empty()) break;
        for (const Polygon& loop : loops) rings.push_back({PathRole::fibre, true, loop});
    }
    return rings;
}

// The region of `part` more than W from every path (W plus a hair: see band_margin_mm).
std::vector<Polygon> bare_of(const std::vector<Polygon>& part, const std::vector<Toolpath>& paths,
                             double w) {
    std::vector<std::vector<Eigen::Vector2d>> lines;
    for (const Toolpath& p : paths) {
        std::vector<Eigen::Vector2d> pts = p.points;
        if (p.closed && !pts.empty()) pts.push_back(pts.front());  // thinned as a line, whole
        lines.push_back(thinned(pts, thin_mm));
    }
    if (lines.empty()) return part;
    return region_difference(part, line_band(lines, w + band_margin_mm, {.arc_tolerance_mm = arc_mm}));
}

void lay_into(LaidFibre& laid, const std::vector<Eigen::Vector2d>& points, bool closed,
              double cutter_distance_mm, std::vector<Toolpath>& out) {
    for (LaidPiece& piece : laid.lay(points, closed, cutter_distance_mm))
        out.push_back({PathRole::fibre, piece.closed, std::move(piece.points)});
}

}  // namespace

GapFill fill_gaps(const LayerMesh& layer, const LayerField& field,
                  const std::vector<Toolpath>& laid_paths, LaidFibre& laid,
                  const GapFillOptions& options) {
    GapFill out;
    const double w = options.spacing_mm;
    const double cutter = options.cutter_distance_mm;
    // W/2 inside and a hair: the inset's chords round a re-entrant corner of the outline lie up
    // to 2.25 arc tolerances nearer to it than its arcs.
    const std::vector<Polygon> part =
        offset_region(layer_outline(layer).loops, -w / 2 - 2.25 * arc_mm - 1e-4, {.arc_tolerance_mm = arc_mm});
    if (part.empty()) return out;
    const TriangleLocator where(layer, 2.0);
    std::vector<Eigen::Vector2d> centroid(layer.triangles.size());
    for (std::size_t f = 0; f < layer.triangles.size(); ++f) {
        const auto& t = layer.triangles[f];
        centroid[f] = (layer.vertices[t[0]] + layer.vertices[t[1]] + layer.vertices[t[2]]) / 3;
    }
    // Lines W apart in an island add up to about its area over W, but a sliver narrower than W
    // still holds one along its edge: an island holds nothing that can be laid when both its
    // area is much smaller than a cutter-long ribbon and its edge shorter than two cutters.
    const auto too_small = [&](const std::vector<Polygon>& island) {
        if (region_area(island) >= 0.5 * w * cutter) return false;
        return path_length({PathRole::fibre, true, island.front()}) < 2 * cutter;
    };
    // Zigzag lines along the island's mean stress and along its length, and (first pass) rings:
    // whichever lays the most length along the stress.
    const auto fill_island = [&](const std::vector<Polygon>& island, bool rings,
                                 std::vector<Toolpath>& into) {
        const double axis = long_axis_deg(island);
        const std::optional<double> stress = stress_direction_deg(island, layer, field, centroid);
        std::vector<std::vector<Toolpath>> candidates;
        candidates.push_back(zigzag_fill(island, PathRole::fibre,
                                         {.spacing_mm = w, .angle_deg = stress.value_or(axis)}));
        if (stress)
            candidates.push_back(
                zigzag_fill(island, PathRole::fibre, {.spacing_mm = w, .angle_deg = axis}));
        if (rings) candidates.push_back(island_rings(island, w));
        std::size_t best = 0;
        double most = -1;
        for (std::size_t i = 0; i < candidates.size(); ++i) {
            const double a = aligned_mm(candidates[i], where, field, cutter);
            if (a > most) most = a, best = i;
        }
        if (rings && best == candidates.size() - 1) ++out.ringed_gaps;
        for (const Toolpath& c : candidates[best]) lay_into(laid, c.points, c.closed, cutter, into);
    };

    const std::vector<Polygon> bare = bare_of(part, laid_paths, w);
    std::vector<Toolpath> first;
    for (const std::vector<Polygon>& island : split_islands(bare)) {
        if (too_small(island)) continue;
        ++out.gaps;
        fill_island(island, true, first);
    }
    // Then what that left (rings pinch into pieces shorter than the cutter; zigzag lines end
    // short of a curved edge): zigzag lines there.
    out.paths = first;
    for (const std::vector<Polygon>& island : split_islands(bare_of(bare, first, w)))
        if (!too_small(island)) fill_island(island, false, out.paths);
    return out;
}

}  // namespace fibrecell::planner
