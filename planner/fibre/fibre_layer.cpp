#include "planner/fibre/fibre_layer.hpp"

#include "planner/fibre/adaptive_isocurves.hpp"
#include "planner/fibre/layer_pieces.hpp"
#include "planner/fibre/scalar_field.hpp"
#include "planner/stopwatch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fibrecell::planner {

std::vector<Toolpath> order_for_travel(std::vector<Toolpath> paths, const Eigen::Vector2d& from) {
    std::vector<Toolpath> ordered;
    ordered.reserve(paths.size());
    std::vector<char> done(paths.size(), 0);
    Eigen::Vector2d at = from;
    for (std::size_t k = 0; k < paths.size(); ++k) {
        std::size_t best = 0;
        bool reverse = false;
        double best_d = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < paths.size(); ++i) {
            if (done[i] || paths[i].points.empty()) continue;
            const double d_front = (paths[i].points.front() - at).squaredNorm();
            if (d_front < best_d) best_d = d_front, best = i, reverse = false;
            const double d_back = (paths[i].points.back() - at).squaredNorm();
            if (!paths[i].closed && d_back < best_d) best_d = d_back, best = i, reverse = true;
        }
        if (!std::isfinite(best_d)) break;
        done[best] = 1;
        Toolpath p = std::move(paths[best]);
        if (reverse) std::reverse(p.points.begin(), p.points.end());
        at = p.closed ? p.points.front() : p.points.back();
        ordered.push_back(std::move(p));
    }
    return ordered;
}

FibreLayer plan_fibre_layer(const LayerMesh& layer, const std::vector<Eigen::Vector3d>& v_e,
                            const std::vector<double>& sigma_e,
                            const std::vector<std::uint8_t>& v_defined,
                            const FibreLayerOptions& options) {
    FibreLayer out;
    Stopwatch clock;
    out.field = layer_field(layer, v_e, sigma_e, v_defined, options.field);
    out.timings.vector_field = clock.lap();

    std::vector<Toolpath> paths;
    out.min_spacing_mm = std::numeric_limits<double>::infinity();
    for (const LayerPiece& piece : split_pieces(layer)) {
        const bool loaded = std::any_of(
            piece.mesh.triangle_tet.begin(), piece.mesh.triangle_tet.end(),
            [&](int tet) { return v_defined[tet] && sigma_e[tet] > options.min_tension; });
        if (!loaded) continue;
        std::vector<Eigen::Vector2d> u;
        u.reserve(piece.face_of_layer.size());
        for (int f : piece.face_of_layer) u.push_back(out.field.u_f[f]);
        clock.lap();
        const std::vector<double> s = scalar_field(piece.mesh, u);
        out.timings.scalar_field += clock.lap();
        const AdaptiveIsocurves curves =
            adaptive_isocurves(piece.mesh, s, {.spacing_mm = options.spacing_mm});
        out.timings.extraction += clock.lap();
        if (curves.count == 0) continue;
        if (curves.count > 1)
            out.min_spacing_mm = std::min(out.min_spacing_mm, curves.min_distance_mm);
        for (const Polyline& c : curves.curves) {
            if (polyline_length(c) < options.cutter_distance_mm) {
                ++out.dropped_short;
                continue;
            }
            paths.push_back({PathRole::fibre, c.closed, c.points});
        }
    }
    if (paths.empty())
        out.warnings.push_back("layer at z = " + std::to_string(layer.z) +
                               ": no fibre path (no usable tension, or every isocurve shorter "
                               "than the cutter distance)");
    clock.lap();
    out.paths = order_for_travel(std::move(paths));
    out.timings.connection = clock.lap();
    if (!std::isfinite(out.min_spacing_mm)) out.min_spacing_mm = 0;
    return out;
}

}  // namespace fibrecell::planner
