#include "planner/layers/triangle_locator.hpp"

#include <cmath>

namespace fibrecell::planner {
namespace {

long long cell_key(long x, long y) {
    return (static_cast<long long>(x) << 32) ^ (static_cast<long long>(y) & 0xffffffffLL);
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

TriangleLocator::TriangleLocator(const LayerMesh& layer, double cell_mm)
    : layer_(layer), cell_(cell_mm) {
    for (std::size_t f = 0; f < layer.triangles.size(); ++f) {
        Eigen::Vector2d lo = layer.vertices[layer.triangles[f][0]], hi = lo;
        for (int v : layer.triangles[f]) {
            lo = lo.cwiseMin(layer.vertices[v]);
            hi = hi.cwiseMax(layer.vertices[v]);
        }
        for (long x = index(lo.x()); x <= index(hi.x()); ++x)
            for (long y = index(lo.y()); y <= index(hi.y()); ++y)
                cells_[cell_key(x, y)].push_back(static_cast<int>(f));
    }
}

int TriangleLocator::locate(const Eigen::Vector2d& p) const {
    const auto it = cells_.find(cell_key(index(p.x()), index(p.y())));
    if (it == cells_.end()) return -1;
    for (int f : it->second)
        if (contains(f, p)) return f;
    return -1;
}

double TriangleLocator::interpolate(const std::vector<double>& per_vertex, const Eigen::Vector2d& p,
                                    double outside) const {
    const int f = locate(p);
    if (f < 0) return outside;
    const auto& t = layer_.triangles[f];
    const Eigen::Vector2d a = layer_.vertices[t[0]], b = layer_.vertices[t[1]],
                          c = layer_.vertices[t[2]];
    const double area = cross(b - a, c - a);
    const double wb = cross(p - a, c - a) / area, wc = cross(b - a, p - a) / area;
    return (1 - wb - wc) * per_vertex[t[0]] + wb * per_vertex[t[1]] + wc * per_vertex[t[2]];
}

bool TriangleLocator::contains(int f, const Eigen::Vector2d& p) const {
    const auto& t = layer_.triangles[f];
    auto side = [&](int a, int b) {
        return cross(layer_.vertices[b] - layer_.vertices[a], p - layer_.vertices[a]);
    };
    const double tol = -1e-9;  // points on an edge belong to both triangles
    return side(t[0], t[1]) >= tol && side(t[1], t[2]) >= tol && side(t[2], t[0]) >= tol;
}

long TriangleLocator::index(double v) const {
    return std::lround(std::floor(v / cell_));
}

}  // namespace fibrecell::planner
