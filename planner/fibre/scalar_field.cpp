#include "planner/fibre/scalar_field.hpp"

#include "planner/fibre/triangle_gradients.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <array>
#include <numeric>
#include <stdexcept>
#include <string>

namespace fibrecell::planner {
namespace {

// Union-find over vertices joined by triangles: the separate pieces of a layer.
std::vector<int> piece_roots(const LayerMesh& layer) {
    std::vector<int> parent(layer.vertices.size());
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    for (const auto& t : layer.triangles) {
        parent[find(t[1])] = find(t[0]);
        parent[find(t[2])] = find(t[0]);
    }
    for (std::size_t v = 0; v < parent.size(); ++v) parent[v] = find(static_cast<int>(v));
    return parent;
}

}  // namespace

Eigen::Vector2d triangle_gradient(const LayerMesh& layer, const std::vector<double>& s, int f) {
    const TriangleGradients g = triangle_gradients(layer, f);
    const auto& t = layer.triangles[f];
    return s[t[0]] * g.grad[0] + s[t[1]] * g.grad[1] + s[t[2]] * g.grad[2];
}

std::vector<double> scalar_field(const LayerMesh& layer, const std::vector<Eigen::Vector2d>& u_f) {
    std::vector<Eigen::Vector2d> rotated;  // u rotated by +90 degrees: isocurves run along u
    rotated.reserve(u_f.size());
    for (const auto& u : u_f) rotated.emplace_back(-u.y(), u.x());
    return fit_gradient(layer, rotated);
}

std::vector<double> fit_gradient(const LayerMesh& layer,
                                 const std::vector<Eigen::Vector2d>& target) {
    const int nv = static_cast<int>(layer.vertices.size());
    // Pin the first vertex of every piece (s = 0 there); the others are unknowns.
    const std::vector<int> root = piece_roots(layer);
    std::vector<int> unknown(nv, -1);
    int n = 0;
    for (int v = 0; v < nv; ++v)
        if (root[v] != v) unknown[v] = n++;

    // Normal equations of the least-squares fit: (sum_f A G^T G) s = sum_f A G^T target_f.
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(layer.triangles.size() * 9);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
    for (std::size_t f = 0; f < layer.triangles.size(); ++f) {
        const TriangleGradients g = triangle_gradients(layer, static_cast<int>(f));
        const auto& t = layer.triangles[f];
        for (int a = 0; a < 3; ++a) {
            const int ia = unknown[t[a]];
            if (ia < 0) continue;
            rhs[ia] += g.area * g.grad[a].dot(target[f]);
            for (int b = 0; b < 3; ++b)
                if (const int ib = unknown[t[b]]; ib >= 0)
                    entries.emplace_back(ia, ib, g.area * g.grad[a].dot(g.grad[b]));
        }
    }
    std::vector<double> s(nv, 0.0);
    if (n == 0) return s;
    Eigen::SparseMatrix<double> k(n, n);
    k.setFromTriplets(entries.begin(), entries.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(k);
    if (solver.info() != Eigen::Success)
        throw std::runtime_error("layer at z = " + std::to_string(layer.z) +
                                 ": the scalar-field system could not be factorised");
    const Eigen::VectorXd x = solver.solve(rhs);
    for (int v = 0; v < nv; ++v)
        if (unknown[v] >= 0) s[v] = x[unknown[v]];
    return s;
}

}  // namespace fibrecell::planner
