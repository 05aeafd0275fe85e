#pragma once
// Checks shared by the layer tests: areas, connectivity and conformity of a sliced layer.

#include "planner/layers/layer_mesh.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

namespace fibrecell::planner::test {

inline double triangle_area(const LayerMesh& m, const std::array<int, 3>& t) {
    const Eigen::Vector2d &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    return 0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
}

inline double area_sum(const LayerMesh& m) {
    double sum = 0;
    for (const auto& t : m.triangles) sum += triangle_area(m, t);
    return sum;
}

inline double min_triangle_area(const LayerMesh& m) {
    double lo = INFINITY;
    for (const auto& t : m.triangles) lo = std::min(lo, triangle_area(m, t));
    return lo;
}

// Number of triangle groups connected through shared edges.
inline int edge_connected_components(const LayerMesh& m) {
    std::vector<int> parent(m.triangles.size());
    std::iota(parent.begin(), parent.end(), 0);
    auto root = [&](int i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    std::map<std::pair<int, int>, int> first_use;
    for (int f = 0; f < static_cast<int>(m.triangles.size()); ++f) {
        for (int e = 0; e < 3; ++e) {
            const int u = m.triangles[f][e], v = m.triangles[f][(e + 1) % 3];
            auto [it, fresh] = first_use.emplace(std::minmax(u, v), f);
            if (!fresh) parent[root(f)] = root(it->second);
        }
    }
    int count = 0;
    for (int f = 0; f < static_cast<int>(parent.size()); ++f) count += root(f) == f;
    return count;
}

// Conforming and consistently oriented: no directed edge is used twice, so every edge borders one
// triangle, or two that run it in opposite directions.
inline bool edges_conform(const LayerMesh& m) {
    std::vector<std::uint64_t> directed;  // (from, to) packed: sorts fast even unoptimised
    directed.reserve(3 * m.triangles.size());
    for (const auto& t : m.triangles)
        for (int e = 0; e < 3; ++e)
            directed.push_back(static_cast<std::uint64_t>(t[e]) << 32 |
                               static_cast<std::uint32_t>(t[(e + 1) % 3]));
    std::sort(directed.begin(), directed.end());
    return std::adjacent_find(directed.begin(), directed.end()) == directed.end();
}

// No two mesh vertices at the same position (points of neighbouring tets were shared).
inline bool vertices_distinct(const LayerMesh& m) {
    std::vector<std::pair<double, double>> p;
    for (const auto& v : m.vertices) p.emplace_back(v.x(), v.y());
    std::sort(p.begin(), p.end());
    return std::adjacent_find(p.begin(), p.end()) == p.end();
}

inline bool loop_has_repeated_point(const Polygon& loop) {
    std::vector<std::pair<double, double>> p;
    for (const auto& v : loop) p.emplace_back(v.x(), v.y());
    std::sort(p.begin(), p.end());
    return std::adjacent_find(p.begin(), p.end()) != p.end();
}

inline double perimeter(const Polygon& loop) {
    double sum = 0;
    for (std::size_t i = 0; i < loop.size(); ++i)
        sum += (loop[(i + 1) % loop.size()] - loop[i]).norm();
    return sum;
}

}  // namespace fibrecell::planner::test
