#include "planner/fibre/boundary_conformal.hpp"

#include "planner/fibre/segment_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fibrecell::planner {
namespace {

struct CutEnd {
    PieceEnd end;
    int curve = -1;  // the link curve it lies on
    double arc = 0;  // arc length along that curve [mm]
};

// Step 2 on the true outline: the runs of every stress curve inside the stress region, each an
// open piece (a closed curve wholly inside stays closed); `cut` collects the ends of open pieces.
void clip_to_region(const std::vector<Polyline>& stress, const std::vector<Polygon>& region,
                    std::vector<Polyline>& pieces, std::vector<PieceEnd>& cut) {
    const RegionClip clip(region);
    for (const Polyline& curve : stress) {
        ClippedRuns clipped = clip(curve.points, curve.closed);
        for (auto& run : clipped.runs) {
            const int id = static_cast<int>(pieces.size());
            pieces.push_back({std::move(run), clipped.closed_inside, curve.level});
            if (clipped.closed_inside) continue;
            cut.push_back({id, false});
            cut.push_back({id, true});
        }
    }
}

// Where each cut end lies along the link curves (the nearest point of their segments).
std::vector<CutEnd> place_on_links(const std::vector<Polyline>& pieces,
                                   const std::vector<PieceEnd>& cut,
                                   const std::vector<Polyline>& link_curves, double w) {
    struct SegmentAt {
        int curve;
        double arc;
    };
    std::vector<SegmentAt> at;
    SegmentGrid grid(w);
    for (int c = 0; c < static_cast<int>(link_curves.size()); ++c) {
        const auto& pts = link_curves[c].points;
        const std::size_t n = pts.size();
        const std::size_t segments = n < 2 ? 0 : (link_curves[c].closed && n > 2 ? n : n - 1);
        double arc = 0;
        for (std::size_t i = 0; i < segments; ++i) {
            const Eigen::Vector2d& a = pts[i];
            const Eigen::Vector2d& b = pts[(i + 1) % n];
            grid.insert({a, b, static_cast<int>(at.size())});
            at.push_back({c, arc});
            arc += (b - a).norm();
        }
    }
    std::vector<CutEnd> out;
    for (const PieceEnd& e : cut) {
        const Eigen::Vector2d& p = end_point(pieces, e);
        double best = 0.5 * w;  // a cut end lies on a link curve; farther means none is there
        CutEnd placed{e};
        grid.around(p, [&](const TaggedSegment& s) {
            const double dist = point_segment_distance(p, s.a, s.b);
            if (dist >= best) return;
            best = dist;
            placed.curve = at[s.tag].curve;
            placed.arc = at[s.tag].arc + (p - s.a).dot((s.b - s.a).normalized());
        });
        if (placed.curve >= 0) out.push_back(placed);
    }
    return out;
}

// The points of a link curve strictly between arc positions a < b (or, on a closed curve,
// from a past the start round to b when wrap).
std::vector<Eigen::Vector2d> link_points(const Polyline& curve, double a, double b, bool wrap) {
    std::vector<Eigen::Vector2d> inner, tail;
    double arc = 0;
    for (std::size_t i = 0; i < curve.points.size(); ++i) {
        if (i > 0) arc += (curve.points[i] - curve.points[i - 1]).norm();
        if (!wrap && arc > a && arc < b) inner.push_back(curve.points[i]);
        if (wrap && arc > a) tail.push_back(curve.points[i]);
        if (wrap && arc < b) inner.push_back(curve.points[i]);
    }
    tail.insert(tail.end(), inner.begin(), inner.end());
    return wrap ? tail : inner;
}

// Step 3: consecutive cut ends on a link curve joined along it, shortest joins first; a join
// never passes another cut end, and none comes nearer than W to a third curve.
std::vector<Link> link_cut_ends(const std::vector<Polyline>& pieces,
                                const std::vector<Polyline>& rings, std::vector<CutEnd> ends,
                                const std::vector<Polyline>& link_curves, double w,
                                double max_link) {
    SegmentGrid obstacles(w);
    for (int i = 0; i < static_cast<int>(pieces.size()); ++i)
        obstacles.insert_polyline(pieces[i].points, false, i);
    for (const auto& r : rings) obstacles.insert_polyline(r.points, r.closed, -1);

    std::sort(ends.begin(), ends.end(), [](const CutEnd& x, const CutEnd& y) {
        return x.curve != y.curve ? x.curve < y.curve : x.arc < y.arc;
    });
    struct Candidate {
        double gap;
        std::size_t i, j;  // indices into ends; j follows i along the curve
        bool wrap;
    };
    std::vector<Candidate> candidates;
    for (std::size_t i = 0; i < ends.size();) {
        std::size_t k = i;
        while (k < ends.size() && ends[k].curve == ends[i].curve) ++k;
        const Polyline& curve = link_curves[ends[i].curve];
        for (std::size_t a = i; a + 1 < k; ++a)
            candidates.push_back({ends[a + 1].arc - ends[a].arc, a, a + 1, false});
        if (curve.closed && k - i > 2) {
            const double length = polyline_length(curve);
            candidates.push_back({length - ends[k - 1].arc + ends[i].arc, k - 1, i, true});
        }
        i = k;
    }
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& x, const Candidate& y) { return x.gap < y.gap; });

    ChainSets chains(pieces.size());
    std::vector<char> used(ends.size(), 0);
    std::vector<Link> links;
    for (const Candidate& c : candidates) {
        if (c.gap > max_link || used[c.i] || used[c.j]) continue;
        const CutEnd& from = ends[c.i];
        const CutEnd& to = ends[c.j];
        Link link{from.end, to.end, link_points(link_curves[from.curve], from.arc, to.arc, c.wrap)};
        bool clear = true;
        for (const auto& p : link.between)
            obstacles.around(p, [&](const TaggedSegment& s) {
                if (s.tag != from.end.piece && s.tag != to.end.piece &&
                    point_segment_distance(p, s.a, s.b) < w)
                    clear = false;
            });
        if (!clear || !join_keeps_spacing(pieces, links, link, w) ||
            !chains.try_join(from.end, to.end))
            continue;
        used[c.i] = used[c.j] = 1;
        links.push_back(std::move(link));
    }
    return links;
}

}  // namespace

BoundaryConformal conform_to_boundary(const FibreRegion& region,
                                      const std::vector<Polyline>& stress,
                                      const BoundaryConformalOptions& options) {
    const double w = options.spacing_mm;
    BoundaryConformal out;
    out.boundary = region.rings;
    std::vector<PieceEnd> cut;
    clip_to_region(stress, region.stress, out.pieces, cut);
    if (region.link_curves.empty()) return out;
    const double max_link = options.max_link_mm > 0 ? options.max_link_mm : 6 * w;
    out.links = link_cut_ends(out.pieces, out.boundary,
                              place_on_links(out.pieces, cut, region.link_curves, w),
                              region.link_curves, w, max_link);
    return out;
}

}  // namespace fibrecell::planner
