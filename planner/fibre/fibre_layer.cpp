#include "planner/fibre/fibre_layer.hpp"

#include "planner/fibre/adaptive_isocurves.hpp"
#include "planner/fibre/layer_pieces.hpp"
#include "planner/fibre/scalar_field.hpp"
#include "planner/stopwatch.hpp"
#include "planner/toolpaths/path_order.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fibrecell::planner {

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
        spdlog::debug(
            "fibre.piece z={:.3f} triangles={} span={:.1f}mm curves={} extractions={} "
            "min_distance={:.3f}mm",
            layer.z, piece.mesh.triangles.size(), curves.geodesic_span_mm, curves.count,
            curves.extractions, curves.min_distance_mm);
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
    out.paths = order_nearest(std::move(paths), Eigen::Vector2d::Zero());
    out.timings.connection = clock.lap();
    if (!std::isfinite(out.min_spacing_mm)) out.min_spacing_mm = 0;
    return out;
}

}  // namespace fibrecell::planner
