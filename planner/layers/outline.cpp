#include "planner/layers/outline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fibrecell::planner {

namespace {

struct DirectedEdge {
    int from, to;
};

// Edges used by exactly one triangle, in the direction that triangle runs them; sorted by
// (from, to).
std::vector<DirectedEdge> boundary_edges(const LayerMesh& layer) {
    struct Use {
        std::uint64_t key;  // undirected (min, max)
        DirectedEdge edge;
    };
    std::vector<Use> uses;
    uses.reserve(3 * layer.triangles.size());
    for (const auto& tri : layer.triangles) {
        for (int e = 0; e < 3; ++e) {
            const int u = tri[e], v = tri[(e + 1) % 3];
            const auto lo = static_cast<std::uint64_t>(std::min(u, v));
            const auto hi = static_cast<std::uint64_t>(std::max(u, v));
            uses.push_back({lo << 32 | hi, {u, v}});
        }
    }
    std::sort(uses.begin(), uses.end(), [](const Use& a, const Use& b) { return a.key < b.key; });
    std::vector<DirectedEdge> boundary;
    for (std::size_t i = 0; i < uses.size();) {
        std::size_t j = i + 1;
        while (j < uses.size() && uses[j].key == uses[i].key) ++j;
        if (j - i == 1) boundary.push_back(uses[i].edge);
        i = j;
    }
    std::sort(boundary.begin(), boundary.end(), [](const DirectedEdge& a, const DirectedEdge& b) {
        return a.from != b.from ? a.from < b.from : a.to < b.to;
    });
    return boundary;
}

// Clockwise angle from direction `from` to direction `to`, in (0, 2 pi].
double clockwise_angle(const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
    const double ccw = std::atan2(from.x() * to.y() - from.y() * to.x(), from.dot(to));
    const double cw = -ccw;
    return cw <= 0 ? cw + 2 * M_PI : cw;
}

// Splits a closed walk of vertex ids at every vertex it visits twice; each piece is a closed loop.
// stack_slot: per vertex, -1 or its index in the walk's stack; left all -1 again.
void split_at_repeats(const std::vector<int>& walk, std::vector<int>& stack_slot,
                      std::vector<std::vector<int>>& loops) {
    std::vector<int> stack;
    for (int v : walk) {
        if (stack_slot[v] < 0) {
            stack_slot[v] = static_cast<int>(stack.size());
            stack.push_back(v);
            continue;
        }
        const auto start = static_cast<std::size_t>(stack_slot[v]);  // v closes stack[start ..]
        loops.emplace_back(stack.begin() + static_cast<std::ptrdiff_t>(start), stack.end());
        for (std::size_t k = start + 1; k < stack.size(); ++k) stack_slot[stack[k]] = -1;
        stack.resize(start + 1);
    }
    for (int v : stack) stack_slot[v] = -1;
    if (stack.size() >= 3) loops.push_back(std::move(stack));
}

}  // namespace

LayerOutline layer_outline(const LayerMesh& layer) {
    const int vertex_count = static_cast<int>(layer.vertices.size());
    for (std::size_t f = 0; f < layer.triangles.size(); ++f)
        for (int v : layer.triangles[f])
            if (v < 0 || v >= vertex_count)
                throw std::invalid_argument("layer outline: triangle " + std::to_string(f) +
                                            " uses vertex " + std::to_string(v) + " of " +
                                            std::to_string(vertex_count));

    const std::vector<DirectedEdge> boundary = boundary_edges(layer);
    // Outgoing boundary edges of vertex v: boundary[first_out[v] .. first_out[v + 1]).
    std::vector<int> first_out(vertex_count + 1, 0), in_degree(vertex_count, 0);
    for (const DirectedEdge& e : boundary) {
        ++first_out[e.from + 1];
        ++in_degree[e.to];
    }
    for (int v = 0; v < vertex_count; ++v) {
        if (first_out[v + 1] != in_degree[v])
            throw std::invalid_argument("layer outline: the boundary does not close at vertex " +
                                        std::to_string(v) + " (" + std::to_string(in_degree[v]) +
                                        " edges in, " + std::to_string(first_out[v + 1]) +
                                        " out): triangles are not consistently oriented");
        first_out[v + 1] += first_out[v];
    }

    std::vector<char> used(boundary.size(), 0);
    std::vector<std::vector<int>> loops;
    std::vector<int> walk, stack_slot(vertex_count, -1);
    for (std::size_t start = 0; start < boundary.size(); ++start) {
        if (used[start]) continue;
        walk.clear();
        std::size_t e = start;
        while (true) {
            used[e] = 1;
            const auto [u, v] = boundary[e];
            walk.push_back(u);
            if (v == boundary[start].from) break;
            // Next edge out of v: the only unused one, or the first clockwise from the way back.
            const Eigen::Vector2d back = layer.vertices[u] - layer.vertices[v];
            std::size_t next = boundary.size();
            double best = INFINITY;
            for (int k = first_out[v]; k < first_out[v + 1]; ++k) {
                if (used[k]) continue;
                const double angle =
                    clockwise_angle(back, layer.vertices[boundary[k].to] - layer.vertices[v]);
                if (next == boundary.size() || angle < best) next = k, best = angle;
            }
            if (next == boundary.size())  // cannot happen when in and out degrees match
                throw std::logic_error("layer outline: boundary walk got stuck");
            e = next;
        }
        split_at_repeats(walk, stack_slot, loops);
    }

    LayerOutline outline;
    outline.loops.reserve(loops.size());
    for (const auto& loop : loops) {
        if (loop.size() < 3) continue;
        Polygon polygon;
        polygon.reserve(loop.size());
        for (int v : loop) polygon.push_back(layer.vertices[v]);
        outline.loops.push_back(std::move(polygon));
    }
    return outline;
}

double signed_area(const Polygon& loop) {
    double twice = 0;
    for (std::size_t i = 0, n = loop.size(); i < n; ++i) {
        const Eigen::Vector2d& a = loop[i];
        const Eigen::Vector2d& b = loop[(i + 1) % n];
        twice += a.x() * b.y() - a.y() * b.x();
    }
    return 0.5 * twice;
}

}  // namespace fibrecell::planner
