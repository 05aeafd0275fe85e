#include "planner/fibre/isocurves.hpp"

#include <algorithm>
#include <stdexcept>
#include <unordered_map>

namespace fibrecell::planner {
namespace {

// A crossing point lies on a mesh edge; both triangles of the edge find the same key. A crossing
// exactly at a vertex is keyed by the vertex alone, so every edge through it finds one point.
// Bits: 24 for each (vertex index + 1), 16 for the level; a vertex key has zero middle bits.
std::uint64_t edge_key(int a, int b, int level) {
    if (a > b) std::swap(a, b);
    return (static_cast<std::uint64_t>(b + 1) << 40) | (static_cast<std::uint64_t>(a + 1) << 16) |
           static_cast<std::uint64_t>(level);
}
std::uint64_t vertex_key(int v, int level) {
    return (static_cast<std::uint64_t>(v + 1) << 40) | static_cast<std::uint64_t>(level);
}

struct Segment {
    int from, to;  // crossing-point ids
};

}  // namespace

double polyline_length(const Polyline& p) {
    double len = 0;
    for (std::size_t i = 1; i < p.points.size(); ++i) len += (p.points[i] - p.points[i - 1]).norm();
    if (p.closed && p.points.size() > 2) len += (p.points.front() - p.points.back()).norm();
    return len;
}

std::vector<Polyline> extract_isocurves(const LayerMesh& layer, const std::vector<double>& s,
                                        const std::vector<double>& isovalues) {
    if (layer.vertices.size() >= (1u << 24) - 1 || isovalues.size() >= (1u << 16))
        throw std::invalid_argument("isocurves: at most 2^24 vertices and 2^16 levels per layer");
    std::vector<Eigen::Vector2d> points;
    std::vector<int> point_level;
    std::unordered_map<std::uint64_t, int> point_of_edge;
    std::vector<Segment> segments;

    auto crossing = [&](int a, int b, int level) {
        const double iso = isovalues[level];
        const std::uint64_t key = s[a] == iso   ? vertex_key(a, level)
                                  : s[b] == iso ? vertex_key(b, level)
                                                : edge_key(a, b, level);
        const auto [it, inserted] = point_of_edge.try_emplace(key, static_cast<int>(points.size()));
        if (inserted) {
            const double t = (iso - s[a]) / (s[b] - s[a]);
            points.push_back(layer.vertices[a] + t * (layer.vertices[b] - layer.vertices[a]));
            point_level.push_back(level);
        }
        return it->second;
    };

    for (const auto& tri : layer.triangles) {
        const double lo = std::min({s[tri[0]], s[tri[1]], s[tri[2]]});
        const double hi = std::max({s[tri[0]], s[tri[1]], s[tri[2]]});
        // Only the isovalues inside this triangle's range: O(F + output), not O(F * levels).
        auto first = std::upper_bound(isovalues.begin(), isovalues.end(), lo);
        // An isovalue equal to lo: every vertex is "above" it, no crossing.
        for (auto it = first; it != isovalues.end() && *it <= hi; ++it) {
            const int level = static_cast<int>(it - isovalues.begin());
            const double iso = *it;
            // Walk the edges counter-clockwise; an edge going from below to above (or back)
            // holds a crossing. Ordering the segment as (below->above, above->below) keeps
            // higher s on the left of every curve.
            int enter = -1, leave = -1;
            for (int k = 0; k < 3; ++k) {
                const int a = tri[k], b = tri[(k + 1) % 3];
                const bool a_above = s[a] >= iso, b_above = s[b] >= iso;
                if (a_above == b_above) continue;
                if (!a_above)
                    enter = crossing(a, b, level);
                else
                    leave = crossing(a, b, level);
            }
            // Both crossings at one vertex: the curve only touches this triangle.
            if (enter >= 0 && leave >= 0 && enter != leave) segments.push_back({leave, enter});
        }
    }

    // Chain segments into polylines: each point has at most one outgoing and one incoming.
    const std::size_t np = points.size();
    std::vector<int> next(np, -1), prev(np, -1);
    for (const Segment& seg : segments) {
        next[seg.from] = seg.to;
        prev[seg.to] = seg.from;
    }
    std::vector<char> used(np, 0);
    std::vector<Polyline> curves;
    auto walk = [&](int start, bool closed) {
        Polyline p;
        p.level = point_level[start];
        p.closed = closed;
        for (int q = start; q >= 0 && !used[q]; q = next[q]) {
            used[q] = 1;
            p.points.push_back(points[q]);
        }
        if (p.points.size() >= 2) curves.push_back(std::move(p));
    };
    for (std::size_t q = 0; q < np; ++q)  // open curves start on the boundary
        if (prev[q] < 0 && !used[q]) walk(static_cast<int>(q), false);
    for (std::size_t q = 0; q < np; ++q)  // what is left are loops
        if (!used[q]) walk(static_cast<int>(q), true);
    return curves;
}

}  // namespace fibrecell::planner
