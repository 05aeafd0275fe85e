#include "planner/fibre/ring_attach.hpp"

#include "planner/fibre/curve_spacing.hpp"
#include "planner/fibre/segment_grid.hpp"
#include "planner/toolpaths/polygon_offset.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace fibrecell::planner {
namespace {

double length_of(const Polyline& p) {
    double l = 0;
    for (std::size_t i = 1; i < p.points.size(); ++i) l += (p.points[i] - p.points[i - 1]).norm();
    if (p.closed && p.points.size() > 1) l += (p.points.front() - p.points.back()).norm();
    return l;
}

// The ways a ring can be laid from a link arriving near `from`: an arc from its nearer end, a
// closed ring from its nearest point either way round, stopped `gap` before it comes back.
std::vector<std::vector<Eigen::Vector2d>> ring_orders(const Polyline& ring,
                                                      const Eigen::Vector2d& from, double gap) {
    const auto& r = ring.points;
    if (!ring.closed) {
        std::vector<Eigen::Vector2d> order = r;
        if ((r.back() - from).norm() < (r.front() - from).norm())
            std::reverse(order.begin(), order.end());
        return {order};
    }
    std::size_t k = 0;
    for (std::size_t i = 1; i < r.size(); ++i)
        if ((r[i] - from).squaredNorm() < (r[k] - from).squaredNorm()) k = i;
    std::vector<std::vector<Eigen::Vector2d>> out;
    for (int step : {1, -1}) {
        std::vector<Eigen::Vector2d> order{r[k]};
        const double total = length_of(ring);
        double along = 0;
        for (std::size_t n = 1; n < r.size(); ++n) {
            const std::size_t i = (k + r.size() + static_cast<std::size_t>(step) * n) % r.size();
            along += (r[i] - order.back()).norm();
            if (along > total - gap) break;
            order.push_back(r[i]);
        }
        out.push_back(std::move(order));
    }
    return out;
}

// The free ends of open paths within reach of the ring, nearest first: (path, last end?).
struct End {
    double distance;
    std::size_t path;
    bool last;
};

std::vector<End> ends_near(const std::vector<Polyline>& paths, const Polyline& ring, double reach) {
    std::vector<End> out;
    for (std::size_t i = 0; i < paths.size(); ++i) {
        if (paths[i].closed || paths[i].points.size() < 2) continue;
        for (bool last : {false, true}) {
            const Eigen::Vector2d e = last ? paths[i].points.back() : paths[i].points.front();
            double d = std::numeric_limits<double>::infinity();
            if (ring.closed)
                for (const auto& q : ring.points) d = std::min(d, (q - e).norm());
            else
                d = std::min((ring.points.front() - e).norm(), (ring.points.back() - e).norm());
            if (d <= reach) out.push_back({d, i, last});
        }
    }
    std::sort(out.begin(), out.end(),
              [](const End& a, const End& b) { return a.distance < b.distance; });
    return out;
}

}  // namespace

std::size_t attach_short_rings(std::vector<Polyline>& paths, std::vector<Polyline>& rings,
                               const std::vector<Polygon>& part, const RingAttachOptions& options,
                               std::vector<Eigen::Vector2d>* joined_at) {
    const double w = options.spacing_mm;
    const double reach = options.reach_mm > 0 ? options.reach_mm : 3 * w;
    std::size_t attached = 0;
    std::optional<RegionClip> inside_part;  // made when a ring is short enough to attach
    for (std::size_t r = 0; r < rings.size();) {
        if (length_of(rings[r]) >= options.cutter_distance_mm || rings[r].points.size() < 2) {
            ++r;
            continue;
        }
        // Everything a link must keep W from, tagged: paths by index, rings by -1 - index.
        SegmentGrid others(w);
        for (std::size_t i = 0; i < paths.size(); ++i)
            others.insert_polyline(paths[i].points, paths[i].closed, static_cast<int>(i));
        for (std::size_t i = 0; i < rings.size(); ++i)
            others.insert_polyline(rings[i].points, rings[i].closed, -1 - static_cast<int>(i));

        bool done = false;
        for (const End& end : ends_near(paths, rings[r], reach)) {
            std::vector<Eigen::Vector2d> fibre = paths[end.path].points;
            if (!end.last) std::reverse(fibre.begin(), fibre.end());
            const Eigen::Vector2d e = fibre.back();
            for (const auto& order : ring_orders(rings[r], e, 1.5 * w)) {
                const Eigen::Vector2d q = order.front();
                if (!inside_part) inside_part.emplace(part);
                if (!inside_part->holds_segment(e, q)) continue;
                bool clear = true;
                const int n = std::max(1, static_cast<int>(std::ceil((q - e).norm() / (w / 4))));
                for (int k = 1; k < n && clear; ++k) {
                    const Eigen::Vector2d x = e + (q - e) * (double(k) / n);
                    others.around(x, [&](const TaggedSegment& s) {
                        const bool own = s.tag == static_cast<int>(end.path) ||
                                         s.tag == -1 - static_cast<int>(r);
                        if (!own && point_segment_distance(x, s.a, s.b) < w) clear = false;
                    });
                }
                if (!clear) continue;
                std::vector<Eigen::Vector2d> joined = fibre;
                joined.insert(joined.end(), order.begin(), order.end());
                // Still too short to cut, it would be dropped whole, the ring with it.
                if (length_of({joined, false, 0}) < options.cutter_distance_mm) continue;
                if (min_fibre_spacing({joined}, {0}, 4 * w, w) < w * (1 - 1e-9)) continue;
                paths[end.path].points = std::move(joined);
                done = true;
                break;
            }
            if (done) break;
        }
        if (done) {
            if (joined_at) joined_at->push_back(rings[r].points.front());
            rings.erase(rings.begin() + static_cast<std::ptrdiff_t>(r));
            ++attached;
        } else {
            ++r;
        }
    }
    return attached;
}

}  // namespace fibrecell::planner
