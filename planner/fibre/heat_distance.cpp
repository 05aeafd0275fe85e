#include "planner/fibre/heat_distance.hpp"

#include "planner/fibre/scalar_field.hpp"
#include "planner/fibre/triangle_gradients.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

namespace fibrecell::planner {

std::vector<double> heat_distance(const LayerMesh& layer, const std::vector<int>& sources,
                                  const HeatDistanceOptions& options) {
    const int nv = static_cast<int>(layer.vertices.size());
    std::vector<double> distance(nv, std::numeric_limits<double>::infinity());
    if (sources.empty() || layer.triangles.empty()) return distance;
    for (int s : sources)
        if (s < 0 || s >= nv)
            throw std::invalid_argument("heat distance: source vertex out of range");

    // Step size from the mesh: t = h^2 with h the mean edge length.
    double edge_sum = 0;
    for (const auto& t : layer.triangles)
        for (int k = 0; k < 3; ++k)
            edge_sum += (layer.vertices[t[k]] - layer.vertices[t[(k + 1) % 3]]).norm();
    const double h = edge_sum / (3.0 * static_cast<double>(layer.triangles.size()));
    const double time = options.time_factor * h * h;

    // I. Heat flow (M + t K) u = delta_sources, backward Euler, lumped mass M, stiffness K.
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(layer.triangles.size() * 12);
    for (int f = 0; f < static_cast<int>(layer.triangles.size()); ++f) {
        const TriangleGradients g = triangle_gradients(layer, f);
        const auto& t = layer.triangles[f];
        for (int a = 0; a < 3; ++a) {
            entries.emplace_back(t[a], t[a], g.area / 3.0);
            for (int b = 0; b < 3; ++b)
                entries.emplace_back(t[a], t[b], time * g.area * g.grad[a].dot(g.grad[b]));
        }
    }
    // A vertex no triangle uses would leave an empty row: pin it with a unit diagonal.
    std::vector<char> used(nv, 0);
    for (const auto& t : layer.triangles)
        for (int v : t) used[v] = 1;
    for (int v = 0; v < nv; ++v)
        if (!used[v]) entries.emplace_back(v, v, 1.0);
    Eigen::SparseMatrix<double> system(nv, nv);
    system.setFromTriplets(entries.begin(), entries.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> heat(system);
    if (heat.info() != Eigen::Success)
        throw std::runtime_error("heat distance: the heat system could not be factorised");
    Eigen::VectorXd delta = Eigen::VectorXd::Zero(nv);
    for (int s : sources) delta[s] = 1.0;
    const Eigen::VectorXd u = heat.solve(delta);

    // II. The unit field pointing away from the sources: X = -grad u / |grad u|.
    std::vector<Eigen::Vector2d> away(layer.triangles.size(), Eigen::Vector2d::Zero());
    for (int f = 0; f < static_cast<int>(layer.triangles.size()); ++f) {
        const TriangleGradients g = triangle_gradients(layer, f);
        const auto& t = layer.triangles[f];
        const Eigen::Vector2d grad =
            u[t[0]] * g.grad[0] + u[t[1]] * g.grad[1] + u[t[2]] * g.grad[2];
        if (grad.norm() > 0) away[f] = -grad.normalized();  // no heat reached: no direction
    }

    // III. The field whose gradient best matches X (one pinned vertex per piece), shifted so
    // that the median source of every piece sits at zero: the field is not exactly constant
    // along the sources (heat leaks around their ends), and the median ignores those ends.
    const std::vector<double> phi = fit_gradient(layer, away);
    std::vector<int> piece(nv);
    std::iota(piece.begin(), piece.end(), 0);
    auto find = [&](int x) {
        while (piece[x] != x) x = piece[x] = piece[piece[x]];
        return x;
    };
    for (const auto& t : layer.triangles) {
        piece[find(t[1])] = find(t[0]);
        piece[find(t[2])] = find(t[0]);
    }
    std::unordered_map<int, std::vector<double>> at_sources;  // piece root -> phi at its sources
    for (int s : sources) at_sources[find(s)].push_back(phi[s]);
    std::vector<double> offset(nv, std::numeric_limits<double>::infinity());
    for (auto& [root, values] : at_sources) {
        auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
        std::nth_element(values.begin(), mid, values.end());
        offset[root] = *mid;
    }
    for (int v = 0; v < nv; ++v) {
        const double o = offset[find(v)];
        if (o < std::numeric_limits<double>::infinity()) distance[v] = std::max(0.0, phi[v] - o);
    }
    return distance;
}

}  // namespace fibrecell::planner
