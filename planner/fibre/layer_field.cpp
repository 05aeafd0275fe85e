#include "planner/fibre/layer_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace fibrecell::planner {

std::vector<std::vector<int>> triangle_neighbours(const LayerMesh& layer) {
    struct EdgeRef {
        int a, b, face;
    };
    std::vector<EdgeRef> edges;
    edges.reserve(layer.triangles.size() * 3);
    for (std::size_t f = 0; f < layer.triangles.size(); ++f) {
        const auto& t = layer.triangles[f];
        for (int k = 0; k < 3; ++k) {
            const int a = t[k], b = t[(k + 1) % 3];
            edges.push_back({std::min(a, b), std::max(a, b), static_cast<int>(f)});
        }
    }
    std::sort(edges.begin(), edges.end(), [](const EdgeRef& x, const EdgeRef& y) {
        return std::pair(x.a, x.b) < std::pair(y.a, y.b);
    });
    std::vector<std::vector<int>> out(layer.triangles.size());
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i + 1;
        while (j < edges.size() && edges[j].a == edges[i].a && edges[j].b == edges[i].b) ++j;
        for (std::size_t x = i; x < j; ++x)
            for (std::size_t y = i; y < j; ++y)
                if (x != y) out[edges[x].face].push_back(edges[y].face);
        i = j;
    }
    return out;
}

LayerField layer_field(const LayerMesh& layer, const std::vector<Eigen::Vector3d>& v_e,
                       const std::vector<double>& sigma_e,
                       const std::vector<std::uint8_t>& v_defined,
                       const LayerFieldOptions& options) {
    const std::size_t nf = layer.triangles.size();
    LayerField out;
    out.v_f.assign(nf, Eigen::Vector2d::Zero());
    out.sigma_f.resize(nf);
    out.defined.assign(nf, 0);
    for (std::size_t f = 0; f < nf; ++f) {
        const int e = layer.triangle_tet[f];
        out.sigma_f[f] = sigma_e[e];
        const Eigen::Vector2d projected = v_e[e].head<2>();
        if (v_defined[e] && projected.norm() >= options.min_projected_length) {
            out.v_f[f] = projected.normalized();
            out.defined[f] = 1;
        }
    }
    if (nf == 0) return out;
    out.fixed_face = static_cast<int>(std::max_element(out.sigma_f.begin(), out.sigma_f.end()) -
                                      out.sigma_f.begin());

    // Jacobi sweeps of the local Laplacian (Eq. 3-4): every face takes the mean of its
    // neighbours. A face without a direction yet averages only the neighbours that have one, so
    // undefined regions fill from their rim inwards instead of being diluted by zeros.
    const auto neighbours = triangle_neighbours(layer);
    std::vector<std::uint8_t> known = out.defined;
    std::vector<Eigen::Vector2d> v_next(nf);
    std::vector<double> sigma_next(nf);
    std::vector<std::uint8_t> known_next(nf);
    for (int it = 0; it < options.smoothing_iterations; ++it) {
        for (std::size_t f = 0; f < nf; ++f) {
            double sigma_sum = 0;
            Eigen::Vector2d v_sum = Eigen::Vector2d::Zero();
            int v_count = 0;
            for (int g : neighbours[f]) {
                sigma_sum += out.sigma_f[g];
                if (known[g]) v_sum += out.v_f[g], ++v_count;
            }
            const auto n = static_cast<double>(neighbours[f].size());
            const bool fixed = static_cast<int>(f) == out.fixed_face;
            sigma_next[f] = fixed || n == 0 ? out.sigma_f[f] : sigma_sum / n;
            if (fixed && known[f]) {
                v_next[f] = out.v_f[f];
                known_next[f] = 1;
            } else if (v_count > 0) {
                v_next[f] = v_sum / v_count;
                known_next[f] = 1;
            } else {
                v_next[f] = out.v_f[f];
                known_next[f] = known[f];
            }
        }
        std::swap(out.v_f, v_next);
        std::swap(out.sigma_f, sigma_next);
        std::swap(known, known_next);
    }

    double cap = std::numeric_limits<double>::infinity();
    if (options.sigma_cap_percentile < 100.0) {
        std::vector<double> sorted = out.sigma_f;
        const auto k = static_cast<std::size_t>(options.sigma_cap_percentile / 100.0 *
                                                static_cast<double>(nf - 1));
        std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(k),
                         sorted.end());
        cap = sorted[k];
    }
    out.u_f.assign(nf, Eigen::Vector2d::Zero());
    for (std::size_t f = 0; f < nf; ++f) {
        const double len = out.v_f[f].norm();
        if (!known[f] || len < 1e-12) continue;  // opposite directions cancelled: no information
        out.u_f[f] = std::pow(std::clamp(out.sigma_f[f], 0.0, cap), options.p) * out.v_f[f] / len;
    }
    return out;
}

}  // namespace fibrecell::planner
