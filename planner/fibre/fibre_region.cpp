#include "planner/fibre/fibre_region.hpp"

#include "planner/fibre/segment_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fibrecell::planner {
namespace {

// A vertex of an offset is "on" the selected boundary when its nearest selected segment is as
// far as the offset distance: the nearest outline point is a selected one.
constexpr double kOnTolerance_mm = 0.01;

class SelectedDistance {
  public:
    SelectedDistance(const std::vector<Segment2>& selected, double reach)
        : grid_(reach), reach_(reach) {
        for (const Segment2& s : selected) grid_.insert({s[0], s[1], 0});
    }
    // Distance [mm] to the nearest selected segment, or infinity beyond the reach.
    double operator()(const Eigen::Vector2d& p) const {
        double best = std::numeric_limits<double>::infinity();
        grid_.around(p, [&](const TaggedSegment& s) {
            const double d = point_segment_distance(p, s.a, s.b);
            if (d < reach_) best = std::min(best, d);
        });
        return best;
    }

  private:
    SegmentGrid grid_;
    double reach_;
};

// Points along a-b (a included, b not) no more than `step` apart.
void densify(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double step,
             std::vector<Eigen::Vector2d>& out) {
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
    for (int i = 0; i < n; ++i) out.push_back(a + (b - a) * (static_cast<double>(i) / n));
}

// The parts of each loop whose vertices lie `offset` from the selected boundary: a loop wholly
// on it stays closed, otherwise its runs of such vertices become open curves.
std::vector<Polyline> runs_on_selected(const std::vector<Polygon>& loops,
                                       const SelectedDistance& distance, double offset,
                                       double step) {
    std::vector<Polyline> out;
    for (const Polygon& loop : loops) {
        const std::size_t n = loop.size();
        std::vector<char> on(n);
        for (std::size_t i = 0; i < n; ++i) on[i] = distance(loop[i]) <= offset + kOnTolerance_mm;
        const auto off = std::find(on.begin(), on.end(), 0);
        if (off == on.end()) {
            Polyline ring{.points = {}, .closed = true};
            for (std::size_t i = 0; i < n; ++i)
                densify(loop[i], loop[(i + 1) % n], step, ring.points);
            out.push_back(std::move(ring));
            continue;
        }
        const std::size_t start = static_cast<std::size_t>(off - on.begin());
        Polyline run;
        auto finish = [&] {
            if (run.points.size() >= 2) out.push_back(run);
            run.points.clear();
        };
        for (std::size_t k = 1; k <= n; ++k) {
            const std::size_t i = (start + k) % n;
            if (!on[i]) {
                finish();
                continue;
            }
            const std::size_t next = (i + 1) % n;
            if (on[next])
                densify(loop[i], loop[next], step, run.points);
            else
                run.points.push_back(loop[i]);
        }
        finish();
    }
    return out;
}

}  // namespace

FibreRegion fibre_region(const LayerOutline& outline, const std::vector<Segment2>& selected,
                         const FibreRegionOptions& options) {
    const double w = options.spacing_mm;
    const OffsetOptions offset{options.arc_tolerance_mm};
    FibreRegion out;
    // Round joins are chords inside their arcs, Clipper's up to 2.25 arc tolerances (it rounds
    // the number of chords, down for a short arc): this much more keeps every chord W/2 from
    // the outline (and 2.5W from the selected boundary).
    const double chord = 2.5 * options.arc_tolerance_mm;
    out.part = offset_region(outline.loops, -(w / 2 + chord), offset);
    if (selected.empty()) {
        out.stress = out.part;
        return out;
    }
    const double ring = options.rings_at_edge ? w / 2 + chord : 1.5 * w;
    out.stress = region_difference(out.part, segment_band(selected, ring + w + chord, offset));
    const SelectedDistance distance(selected, ring + 1.5 * w);
    out.ring_loops = offset_region(outline.loops, -ring, offset);
    out.rings = runs_on_selected(out.ring_loops, distance, ring, w);
    out.link_curves = runs_on_selected(out.stress, distance, ring + w + chord, w);
    return out;
}

}  // namespace fibrecell::planner
