#include "planner/fibre/adaptive_isocurves.hpp"

#include "planner/fibre/curve_spacing.hpp"
#include "planner/fibre/layer_pieces.hpp"
#include "planner/fibre/spacing_trim.hpp"
#include "planner/fibre/triangle_gradients.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fibrecell::planner {
namespace {

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                           const Eigen::Vector2d& b) {
    const Eigen::Vector2d ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    return (p - (a + t * ab)).norm();
}

// Rules out counts n whose isocurves are over-dense inside a single triangle: two neighbouring
// levels crossing one triangle closer than W. Their chords are pieces of the extracted curves
// (the same crossing points extract_isocurves computes), so such an n has d <= W for certain and
// needs no extraction. Only triangles steep enough for two levels Delta apart to come within W
// (|grad s| >= Delta / W) and tall enough to hold two levels (range >= Delta) can do it.
class SingleTriangleCheck {
  public:
    SingleTriangleCheck(const LayerMesh& piece, const std::vector<double>& s, double s_min,
                        double s_max, double w)
        : piece_(piece), s_(s), s_min_(s_min), s_max_(s_max), w_(w) {
        for (std::size_t f = 0; f < piece.triangles.size(); ++f) {
            const auto& t = piece.triangles[f];
            const double lo = std::min({s[t[0]], s[t[1]], s[t[2]]});
            const double hi = std::max({s[t[0]], s[t[1]], s[t[2]]});
            // |grad s| of the linear interpolant: the gradient's norm from two edges.
            const Eigen::Vector2d e1 = piece.vertices[t[1]] - piece.vertices[t[0]];
            const Eigen::Vector2d e2 = piece.vertices[t[2]] - piece.vertices[t[0]];
            const double det = e1.x() * e2.y() - e1.y() * e2.x();
            if (std::abs(det) < 1e-300) continue;
            const double d1 = s[t[1]] - s[t[0]], d2 = s[t[2]] - s[t[0]];
            const Eigen::Vector2d g((d1 * e2.y() - d2 * e1.y()) / det,
                                    (d2 * e1.x() - d1 * e2.x()) / det);
            steep_.push_back({static_cast<int>(f), lo, hi, hi - lo, g.norm()});
        }
        std::sort(steep_.begin(), steep_.end(),
                  [](const Triangle& a, const Triangle& b) { return a.range > b.range; });
    }

    bool overdense(int n) const {
        const double delta = (s_max_ - s_min_) / n;
        // Slightly inside W, so that rounding never rules out a count the extraction would keep.
        const double limit = w_ * (1 - 1e-9);
        for (const Triangle& t : steep_) {
            if (t.range < delta) break;  // sorted: no later one holds two levels either
            if (t.gradient * limit < delta) continue;
            // The levels inside (lo, hi], as extract_isocurves takes them.
            int i = std::max(0, static_cast<int>(std::floor((t.lo - s_min_) / delta - 0.5)) - 1);
            while (i < n && level(i, n) <= t.lo) ++i;
            for (; i + 1 < n && level(i + 1, n) <= t.hi; ++i)
                if (chord_distance(t.face, level(i, n), level(i + 1, n)) < limit) return true;
        }
        return false;
    }

  private:
    struct Triangle {
        int face;
        double lo, hi, range, gradient;
    };

    double level(int i, int n) const { return s_min_ + (0.5 + i) / n * (s_max_ - s_min_); }

    // The chord of level `iso` across the triangle (its two crossing points); false when it only
    // touches a vertex.
    bool chord(int face, double iso, Eigen::Vector2d& p, Eigen::Vector2d& q) const {
        const auto& tri = piece_.triangles[static_cast<std::size_t>(face)];
        int found = 0;
        for (int k = 0; k < 3; ++k) {
            const int a = tri[k], b = tri[(k + 1) % 3];
            if ((s_[a] >= iso) == (s_[b] >= iso)) continue;
            const double t = (iso - s_[a]) / (s_[b] - s_[a]);
            (found++ == 0 ? p : q) =
                piece_.vertices[a] + t * (piece_.vertices[b] - piece_.vertices[a]);
        }
        return found == 2 && (p - q).squaredNorm() > 0;
    }

    double chord_distance(int face, double iso_a, double iso_b) const {
        Eigen::Vector2d a0, a1, b0, b1;
        if (!chord(face, iso_a, a0, a1) || !chord(face, iso_b, b0, b1))
            return std::numeric_limits<double>::infinity();
        return std::min({distance_to_segment(a0, b0, b1), distance_to_segment(a1, b0, b1),
                         distance_to_segment(b0, a0, a1), distance_to_segment(b1, a0, a1)});
    }

    const LayerMesh& piece_;
    const std::vector<double>& s_;
    double s_min_, s_max_, w_;
    std::vector<Triangle> steep_;
};

// The area-weighted q-quantile of |grad s| over the piece's triangles.
double gradient_quantile(const LayerMesh& piece, const std::vector<double>& s, double q) {
    std::vector<std::pair<double, double>> g;  // |grad s|, area
    double total = 0;
    for (int f = 0; f < static_cast<int>(piece.triangles.size()); ++f) {
        const TriangleGradients t = triangle_gradients(piece, f);
        const auto& tri = piece.triangles[static_cast<std::size_t>(f)];
        const Eigen::Vector2d grad =
            s[tri[0]] * t.grad[0] + s[tri[1]] * t.grad[1] + s[tri[2]] * t.grad[2];
        g.emplace_back(grad.norm(), t.area);
        total += t.area;
    }
    std::sort(g.begin(), g.end());
    double area = 0;
    for (const auto& [norm, a] : g)
        if ((area += a) >= q * total) return norm;
    return g.empty() ? 0.0 : g.back().first;
}

}  // namespace

AdaptiveIsocurves adaptive_isocurves(const LayerMesh& piece, const std::vector<double>& s,
                                     const AdaptiveIsocurveOptions& options) {
    AdaptiveIsocurves out;
    if (s.empty()) return out;
    const auto [min_it, max_it] = std::minmax_element(s.begin(), s.end());
    const double s_min = *min_it, s_max = *max_it;
    if (s_max - s_min < options.min_range) return out;

    // Steps 1-2: the geodesic span D from the nodes at s_min to the farthest node at s_max.
    const double tie = 1e-12 * (s_max - s_min);
    std::vector<int> lowest;
    for (std::size_t v = 0; v < s.size(); ++v)
        if (s[v] <= s_min + tie) lowest.push_back(static_cast<int>(v));
    const std::vector<double> dist = edge_distances(piece, lowest);
    for (std::size_t v = 0; v < s.size(); ++v)
        if (s[v] >= s_max - tie) out.geodesic_span_mm = std::max(out.geodesic_span_mm, dist[v]);

    const double w = options.spacing_mm;
    const double cap = 2.0 * w;  // farther than this, the exact distance does not matter
    const double crowding = options.crowded_fraction;
    // measure: the paper's Steps decide on d; a crowded fraction chooses n without it.
    auto extract = [&](int n, bool measure) {
        std::vector<double> isovalues(n);
        for (int i = 0; i < n; ++i) isovalues[i] = s_min + (0.5 + i) / n * (s_max - s_min);
        ++out.extractions;
        out.curves = extract_isocurves(piece, s, isovalues);
        out.count = n;
        out.min_distance_mm = measure ? min_neighbour_distance(out.curves, cap) : 0.0;
    };

    if (crowding > 0 || options.density_scale != 1.0) {
        // Neighbouring levels Delta apart in s lie Delta / |grad s| apart: with Delta = W times
        // the |grad s| that all but the crowded fraction of the area stay below, that area gets
        // curves at least W apart and the rest is cut back to W.
        const double g = gradient_quantile(piece, s, 1 - crowding);
        const double count =
            g > 0 ? std::floor(options.density_scale * (s_max - s_min) / (w * g)) : 1;
        extract(static_cast<int>(std::clamp(count, 1.0, double(options.max_curves))), false);
        double before = 0, after = 0;
        for (const Polyline& c : out.curves) before += polyline_length(c);
        out.curves = trim_to_spacing(out.curves, out.count, {.spacing_mm = w});
        for (const Polyline& c : out.curves) after += polyline_length(c);
        out.trimmed_mm = before - after;
        return out;
    }

    // Steps 3-4: grow n until the curves are over-dense (d <= W).
    int n = std::max(1, static_cast<int>(std::ceil(out.geodesic_span_mm / w)));
    extract(n, true);
    while (out.min_distance_mm > w && n < options.max_curves) {
        n = std::min(options.max_curves,
                     std::max(n + 1, static_cast<int>(std::ceil(n * out.min_distance_mm / w))));
        extract(n, true);
    }
    // Steps 5-6 as the paper states them: n steps down by one from the over-dense count until
    // neighbours are more than W apart (the spacing need not shrink monotonically with n, so a
    // bisection can stop at a far smaller n). Counts over-dense within one triangle are ruled out
    // without an extraction; the first count that is not is extracted and decides.
    if (out.min_distance_mm <= w && n > 1) {
        const SingleTriangleCheck dense(piece, s, s_min, s_max, w);
        while (n > 1) {
            --n;
            if (dense.overdense(n)) {
                ++out.counts_ruled_out;
                continue;
            }
            extract(n, true);  // n = 1 always ends it: a single level has no neighbour
            if (out.min_distance_mm > w) break;
        }
    }
    return out;
}

}  // namespace fibrecell::planner
