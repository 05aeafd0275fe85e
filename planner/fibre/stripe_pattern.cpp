#include "planner/fibre/stripe_pattern.hpp"

#include "planner/progress.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace fibrecell::planner {
namespace {

using Complex = std::complex<double>;
constexpr double two_pi = 2 * std::numbers::pi;

double triangle_area(const LayerMesh& mesh, const std::array<int, 3>& t) {
    const Eigen::Vector2d e1 = mesh.vertices[t[1]] - mesh.vertices[t[0]];
    const Eigen::Vector2d e2 = mesh.vertices[t[2]] - mesh.vertices[t[0]];
    return 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
}

// Vertex v's direction and phase read alongside vertex `ref`'s: where the line field's sign
// flips between them, the direction turned round and the phase conjugated.
struct Aligned {
    Eigen::Vector2d across;
    Complex psi;
    bool flipped;
};
Aligned aligned(const std::vector<Eigen::Vector2d>& across, const std::vector<Complex>& psi,
                int ref, int v) {
    const bool flip = across[v].dot(across[ref]) < 0;
    return {flip ? Eigen::Vector2d(-across[v]) : across[v],
            psi.empty() ? Complex{} : flip ? std::conj(psi[v]) : psi[v], flip};
}

// Per vertex: the direction across the stripes (the phase's gradient), a unit vector whose sign
// means nothing. The faces' directions are averaged as a line field (angles doubled).
std::vector<Eigen::Vector2d> across_directions(const LayerMesh& mesh,
                                               const std::vector<Eigen::Vector2d>& direction_f) {
    std::vector<Complex> doubled(mesh.vertices.size(), Complex{});
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        const Eigen::Vector2d d = direction_f[f];
        const double n = d.norm();
        if (!(n > 0)) continue;
        const Complex z(d.x() / n, d.y() / n);
        const double area = triangle_area(mesh, mesh.triangles[f]);
        for (int v : mesh.triangles[f]) doubled[v] += area * z * z;
    }
    std::vector<Eigen::Vector2d> across(mesh.vertices.size(), Eigen::Vector2d(1, 0));
    for (std::size_t v = 0; v < doubled.size(); ++v) {
        if (std::abs(doubled[v]) == 0) continue;
        const double along = 0.5 * std::arg(doubled[v]);
        across[v] = {-std::sin(along), std::cos(along)};  // the stripes run along `along`
    }
    return across;
}

struct Edge {
    int a = 0, b = 0;    // a < b
    double weight = 0;  // cotangent weight
};

// The mesh's edges with their cotangent weights, and each triangle's edges (opposite its corners).
struct Edges {
    std::vector<Edge> list;
    std::vector<std::array<int, 3>> of_triangle;  // [k]: the edge opposite corner k
};

Edges mesh_edges(const LayerMesh& mesh) {
    Edges out;
    std::map<std::pair<int, int>, int> index;
    out.of_triangle.resize(mesh.triangles.size());
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        const auto& t = mesh.triangles[f];
        for (int k = 0; k < 3; ++k) {
            const int i = t[(k + 1) % 3], j = t[(k + 2) % 3];
            const Eigen::Vector2d u = mesh.vertices[i] - mesh.vertices[t[k]];
            const Eigen::Vector2d v = mesh.vertices[j] - mesh.vertices[t[k]];
            const double cross = std::abs(u.x() * v.y() - u.y() * v.x());
            const double cot = cross > 0 ? u.dot(v) / cross : 0;
            const auto key = std::minmax(i, j);
            auto [it, added] = index.emplace(key, static_cast<int>(out.list.size()));
            if (added) out.list.push_back({key.first, key.second, 0});
            out.list[it->second].weight += 0.5 * cot;
            out.of_triangle[f][k] = it->second;
        }
    }
    return out;
}

// The 2 x 2 real matrix of psi -> e^{i omega} psi, or of psi -> e^{i omega} conj(psi).
Eigen::Matrix2d transport(double omega, bool conjugate) {
    const double c = std::cos(omega), s = std::sin(omega);
    Eigen::Matrix2d m;
    if (conjugate) m << c, s, s, -c;
    else m << c, -s, s, c;
    return m;
}

// The phase change along the edge a -> b wanted by the directions (aligned to each other).
double edge_omega(const LayerMesh& mesh, int a, int b, const Eigen::Vector2d& xa,
                  const Eigen::Vector2d& xb, double frequency) {
    return 0.5 * frequency * (mesh.vertices[b] - mesh.vertices[a]).dot(xa + xb);
}

// psi per vertex: the smallest eigenvector of the stripe energy
// sum_ij w_ij |psi_j - r_ij psi_i|^2 against the lumped mass (inverse iteration).
std::vector<Complex> solve_phase(const LayerMesh& mesh, const Edges& edges,
                                 const std::vector<Eigen::Vector2d>& across, double frequency,
                                 int iterations) {
    const int n = static_cast<int>(mesh.vertices.size());
    std::vector<Eigen::Triplet<double>> a;
    a.reserve(edges.list.size() * 16);
    Eigen::VectorXd mass = Eigen::VectorXd::Zero(2 * n);
    for (const auto& t : mesh.triangles) {
        const double third = triangle_area(mesh, t) / 3;
        for (int v : t) mass[2 * v] += third, mass[2 * v + 1] += third;
    }
    const double mean_mass = std::max(mass.sum() / std::max(1, 2 * n), 1e-300);
    for (const Edge& e : edges.list) {
        // A negative cotangent weight (an obtuse sliver of the slice) would make the energy
        // indefinite; such an edge still ties its ends a little.
        const double w = std::max(e.weight, 1e-3);
        const Aligned b = aligned(across, {}, e.a, e.b);
        const Eigen::Matrix2d m =
            transport(edge_omega(mesh, e.a, e.b, across[e.a], b.across, frequency), b.flipped);
        for (int r = 0; r < 2; ++r) {
            a.emplace_back(2 * e.a + r, 2 * e.a + r, w);
            a.emplace_back(2 * e.b + r, 2 * e.b + r, w);
            for (int c = 0; c < 2; ++c) {
                a.emplace_back(2 * e.b + r, 2 * e.a + c, -w * m(r, c));
                a.emplace_back(2 * e.a + c, 2 * e.b + r, -w * m(r, c));
            }
        }
    }
    // A small shift keeps the factorisation definite when the stripes fit exactly (energy 0); a
    // vertex of no triangle gets a row of its own.
    for (int i = 0; i < 2 * n; ++i)
        a.emplace_back(i, i, mass[i] > 0 ? 1e-8 * mass[i] / mean_mass : 1.0);
    Eigen::SparseMatrix<double> k(2 * n, 2 * n);
    k.setFromTriplets(a.begin(), a.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(k);
    if (solver.info() != Eigen::Success)
        throw std::runtime_error("layer at z = " + std::to_string(mesh.z) +
                                 ": the stripe-pattern system could not be factorised");
    // A fixed start (not random): the same part plans the same stripes.
    Eigen::VectorXd x(2 * n);
    for (int i = 0; i < 2 * n; ++i) x[i] = 1.0 + 0.5 * std::sin(0.7 * i);
    for (int it = 0; it < iterations; ++it) {
        cancellation_point();
        Eigen::VectorXd y = solver.solve(mass.cwiseProduct(x));
        const double norm = std::sqrt(y.dot(mass.cwiseProduct(y)));
        if (!(norm > 0) || !std::isfinite(norm)) break;
        x = y / norm;
    }
    std::vector<Complex> psi(n);
    for (int v = 0; v < n; ++v) psi[v] = {x[2 * v], x[2 * v + 1]};
    return psi;
}

// The phase difference along a -> b: the wanted change plus the solution's own deviation from it
// (in (-pi, pi]). `xa`, `xb` and `psi_a`, `psi_b` read aligned (see Aligned).
double phase_step(const LayerMesh& mesh, int a, int b, const Eigen::Vector2d& xa,
                  const Eigen::Vector2d& xb, const Complex& psi_a, const Complex& psi_b,
                  double frequency) {
    const double omega = edge_omega(mesh, a, b, xa, xb, frequency);
    return omega + std::arg(psi_b * std::conj(std::polar(1.0, omega) * psi_a));
}

// Where an edge's phase (linear from alpha_a at a to alpha_b at b) crosses 2 pi m, as fractions
// along a -> b. A value exactly on a level counts as above it (so the levels in (lo, hi]).
std::vector<double> crossings(double alpha_a, double alpha_b) {
    std::vector<double> t;
    const double lo = std::min(alpha_a, alpha_b), hi = std::max(alpha_a, alpha_b);
    for (double m = std::floor(lo / two_pi) + 1; two_pi * m <= hi; ++m)
        t.push_back((two_pi * m - alpha_a) / (alpha_b - alpha_a));
    std::sort(t.begin(), t.end());
    return t;
}

}  // namespace

StripePattern stripe_pattern(const LayerMesh& piece, const std::vector<Eigen::Vector2d>& direction_f,
                             const StripeOptions& options) {
    StripePattern out;
    if (piece.triangles.empty()) return out;
    const double frequency = two_pi / options.spacing_mm;
    const std::vector<Eigen::Vector2d> across = across_directions(piece, direction_f);
    const Edges edges = mesh_edges(piece);
    const std::vector<Complex> psi = solve_phase(piece, edges, across, frequency, options.iterations);

    // Each edge's crossings once, with the phase read from its end a: a point of a stripe has
    // one id, whichever triangle reaches it.
    std::vector<std::vector<double>> edge_t(edges.list.size());
    std::vector<int> first_id(edges.list.size() + 1, 0);
    for (std::size_t e = 0; e < edges.list.size(); ++e) {
        const Edge& g = edges.list[e];
        const Aligned b = aligned(across, psi, g.a, g.b);
        const double alpha_a = std::arg(psi[g.a]);
        const double alpha_b =
            alpha_a + phase_step(piece, g.a, g.b, across[g.a], b.across, psi[g.a], b.psi, frequency);
        edge_t[e] = crossings(alpha_a, alpha_b);
        first_id[e + 1] = first_id[e] + static_cast<int>(edge_t[e].size());
    }
    std::vector<Eigen::Vector2d> point(static_cast<std::size_t>(first_id.back()));
    for (std::size_t e = 0; e < edges.list.size(); ++e) {
        const Edge& g = edges.list[e];
        for (std::size_t k = 0; k < edge_t[e].size(); ++k)
            point[first_id[e] + k] = piece.vertices[g.a] + edge_t[e][k] * (piece.vertices[g.b] - piece.vertices[g.a]);
    }
    // The crossing of edge e nearest to fraction t along a -> b (its ids run with t).
    const auto nearest = [&](int e, double t) {
        const auto& ts = edge_t[e];
        if (ts.empty()) return -1;
        const auto it = std::lower_bound(ts.begin(), ts.end(), t);
        std::size_t k = static_cast<std::size_t>(it - ts.begin());
        if (k == ts.size() || (k > 0 && t - ts[k - 1] < ts[k] - t)) --k;
        return std::abs(ts[k] - t) < 1e-6 ? first_id[e] + static_cast<int>(k) : -1;
    };

    // Per triangle: the phase at its corners read from corner 0 (directions aligned to it), the
    // stripes as straight pieces between the crossings of its edges. Where the phase winds round
    // the triangle (a branch point) no stripe is drawn.
    std::vector<std::array<int, 2>> link(point.size(), {-1, -1});
    const auto connect = [&](int p, int q) {
        for (int r : {p, q})
            if (link[r][0] >= 0 && link[r][1] >= 0) return;  // a degenerate crossing: skip
        link[p][link[p][0] < 0 ? 0 : 1] = q;
        link[q][link[q][0] < 0 ? 0 : 1] = p;
    };
    for (std::size_t f = 0; f < piece.triangles.size(); ++f) {
        if (f % 256 == 0) cancellation_point();
        const auto& t = piece.triangles[f];
        std::array<Eigen::Vector2d, 3> x;
        std::array<Complex, 3> z;
        for (int k = 0; k < 3; ++k) {
            const Aligned c = aligned(across, psi, t[0], t[k]);
            x[k] = c.across;
            z[k] = c.psi;
        }
        const auto step = [&](int i, int j) {
            return phase_step(piece, t[i], t[j], x[i], x[j], z[i], z[j], frequency);
        };
        const double d01 = step(0, 1), d12 = step(1, 2), d20 = step(2, 0);
        if (std::abs(d01 + d12 + d20) > std::numbers::pi) {
            ++out.singular_triangles;
            continue;
        }
        const std::array<double, 3> alpha = {std::arg(z[0]), std::arg(z[0]) + d01,
                                             std::arg(z[0]) + d01 + d12};
        // For each level, the crossings on the triangle's edges (corner pairs (k+1, k+2)).
        std::map<long, std::vector<int>> at_level;
        for (int k = 0; k < 3; ++k) {
            const int i = (k + 1) % 3, j = (k + 2) % 3;
            const int e = edges.of_triangle[f][k];
            const bool forward = edges.list[e].a == t[i];
            for (double s : crossings(alpha[i], alpha[j])) {
                const double level = alpha[i] + s * (alpha[j] - alpha[i]);
                const int id = nearest(e, forward ? s : 1 - s);
                if (id >= 0) at_level[std::lround(level / two_pi)].push_back(id);
            }
        }
        for (const auto& [level, ids] : at_level)
            if (ids.size() == 2) connect(ids[0], ids[1]);
    }

    // Chains of linked crossings: open ones from their ends first, then the closed ones.
    std::vector<char> used(point.size(), 0);
    const auto walk = [&](int start) {
        Polyline line;
        int prev = -1, at = start;
        while (at >= 0 && !used[at]) {
            used[at] = 1;
            line.points.push_back(point[at]);
            const int next = link[at][0] != prev ? link[at][0] : link[at][1];
            prev = at;
            at = next;
        }
        line.closed = at == start && line.points.size() > 2;
        line.level = static_cast<int>(out.stripes.size());
        if (line.points.size() >= 2) out.stripes.push_back(std::move(line));
    };
    for (std::size_t p = 0; p < point.size(); ++p)
        if (!used[p] && (link[p][0] < 0) != (link[p][1] < 0)) walk(static_cast<int>(p));
    for (std::size_t p = 0; p < point.size(); ++p)
        if (!used[p] && link[p][0] >= 0) walk(static_cast<int>(p));
    return out;
}

}  // namespace fibrecell::planner
