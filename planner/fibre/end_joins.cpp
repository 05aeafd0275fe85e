#include "planner/fibre/end_joins.hpp"

#include "planner/fibre/segment_grid.hpp"
#include "planner/toolpaths/polygon_offset.hpp"

#include <algorithm>

namespace fibrecell::planner {
namespace {

bool same(const PieceEnd& a, const PieceEnd& b) {
    return a.piece == b.piece && a.last == b.last;
}

}  // namespace

std::vector<Link> join_close_ends(const std::vector<Polyline>& pieces,
                                  const std::vector<Link>& taken,
                                  const std::vector<Polyline>& obstacles,
                                  const EndJoinOptions& options) {
    std::vector<PieceEnd> free_ends;
    for (int i = 0; i < static_cast<int>(pieces.size()); ++i) {
        if (pieces[i].closed || pieces[i].points.size() < 2) continue;
        for (bool last : {false, true}) {
            const PieceEnd e{i, last};
            const bool linked = std::any_of(taken.begin(), taken.end(), [&](const Link& l) {
                return same(l.from, e) || same(l.to, e);
            });
            if (!linked) free_ends.push_back(e);
        }
    }
    // Pairs nearer than the gap, through a sort on x (ends are few, pairs fewer).
    std::sort(free_ends.begin(), free_ends.end(), [&](const PieceEnd& a, const PieceEnd& b) {
        return end_point(pieces, a).x() < end_point(pieces, b).x();
    });
    struct Pair {
        double gap;
        std::size_t a, b;
    };
    std::vector<Pair> pairs;
    for (std::size_t a = 0; a < free_ends.size(); ++a) {
        const Eigen::Vector2d& pa = end_point(pieces, free_ends[a]);
        for (std::size_t b = a + 1; b < free_ends.size(); ++b) {
            const Eigen::Vector2d& pb = end_point(pieces, free_ends[b]);
            if (pb.x() - pa.x() >= options.max_gap_mm) break;
            const double gap = (pb - pa).norm();
            if (gap < options.max_gap_mm) pairs.push_back({gap, a, b});
        }
    }
    std::sort(pairs.begin(), pairs.end(),
              [](const Pair& x, const Pair& y) { return x.gap < y.gap; });

    SegmentGrid grid(std::max(options.max_gap_mm, options.clearance_mm));
    for (int i = 0; i < static_cast<int>(pieces.size()); ++i)
        grid.insert_polyline(pieces[i].points, pieces[i].closed, i);
    for (const auto& o : obstacles) grid.insert_polyline(o.points, o.closed, -1);
    for (const Link& l : taken) grid.insert_polyline(l.between, false, -1);

    ChainSets chains(pieces.size());
    for (const Link& l : taken) chains.try_join(l.from, l.to);
    std::vector<char> used(free_ends.size(), 0);
    std::vector<Link> made = taken;  // for the spacing along the fibre through earlier joins
    std::vector<Link> links;
    for (const Pair& p : pairs) {
        if (used[p.a] || used[p.b]) continue;
        const PieceEnd& ea = free_ends[p.a];
        const PieceEnd& eb = free_ends[p.b];
        const Eigen::Vector2d a = end_point(pieces, ea), b = end_point(pieces, eb);
        // The straight link's inner points must keep clear of every other curve.
        bool clear = !options.keep_inside || options.keep_inside->holds_segment(a, b);
        for (double t : {0.25, 0.5, 0.75}) {
            const Eigen::Vector2d x = a + t * (b - a);
            grid.around(x, [&](const TaggedSegment& s) {
                if (s.tag != ea.piece && s.tag != eb.piece &&
                    point_segment_distance(x, s.a, s.b) < options.clearance_mm)
                    clear = false;
            });
        }
        const Link link{ea, eb, {}};
        if (!clear || !join_keeps_spacing(pieces, made, link, options.clearance_mm) ||
            !chains.try_join(ea, eb))
            continue;
        used[p.a] = used[p.b] = 1;
        links.push_back(link);
        made.push_back(link);
    }
    return links;
}

}  // namespace fibrecell::planner
