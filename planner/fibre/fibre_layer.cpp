#include "planner/fibre/fibre_layer.hpp"

#include "planner/fibre/adaptive_isocurves.hpp"
#include "planner/fibre/boundary_conformal.hpp"
#include "planner/fibre/curve_spacing.hpp"
#include "planner/fibre/end_joins.hpp"
#include "planner/fibre/fibre_region.hpp"
#include "planner/fibre/gap_fill.hpp"
#include "planner/fibre/laid_fibre.hpp"
#include "planner/fibre/layer_pieces.hpp"
#include "planner/fibre/path_chains.hpp"
#include "planner/fibre/ring_attach.hpp"
#include "planner/fibre/ring_extend.hpp"
#include "planner/fibre/scalar_field.hpp"
#include "planner/fibre/stripe_pattern.hpp"
#include "planner/layers/outline.hpp"
#include "planner/stopwatch.hpp"
#include "planner/toolpaths/path_order.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <iterator>
#include <tuple>

namespace fibrecell::planner {

namespace {

// The selected outline edges that fall on one piece, as segments of its outline.
std::vector<Segment2> piece_selected(const LayerPiece& piece,
                                     const std::vector<std::array<int, 2>>& layer_edges,
                                     std::size_t layer_vertices) {
    if (layer_edges.empty()) return {};
    std::vector<int> local(layer_vertices, -1);
    for (int v = 0; v < static_cast<int>(piece.vertex_of_layer.size()); ++v)
        local[piece.vertex_of_layer[v]] = v;
    std::vector<Segment2> out;
    for (const auto& [a, b] : layer_edges)
        if (local[a] >= 0 && local[b] >= 0)
            out.push_back({piece.mesh.vertices[local[a]], piece.mesh.vertices[local[b]]});
    return out;
}

// Section 4.4 on one piece: the stress curves clipped to where fibre may lie, boundary rings and
// their links where the piece has chosen boundary, the joins of close ends, then the rings too
// short to cut joined onto neighbouring paths. Adds the paths to `out`, counts its joins.
void connect_piece(const FibreRegion& region, std::vector<Polyline> curves,
                   const FibreLayerOptions& options, FibreLayer& out,
                   std::vector<Toolpath>& paths) {
    const double w = options.spacing_mm;
    BoundaryConformal b = conform_to_boundary(region, curves, {.spacing_mm = w});
    // Links may run along the region's edge, where the curve ends lie: grown by a hair, the
    // region keeps them in.
    const RegionClip link_region(offset_region(region.stress, 1e-4));
    std::vector<Link> close =
        join_close_ends(b.pieces, b.links, b.boundary,
                        {.max_gap_mm = 2 * w, .clearance_mm = w, .keep_inside = &link_region});
    b.links.insert(b.links.end(), close.begin(), close.end());
    out.joins += b.links.size();
    for (const Link& l : b.links)
        out.join_points.push_back(0.5 * (end_point(b.pieces, l.from) + end_point(b.pieces, l.to)));
    std::vector<Polyline> chains = join_pieces(b.pieces, b.links);
    out.rings_joined +=
        attach_short_rings(chains, b.boundary, region.part,
                           {.spacing_mm = w, .cutter_distance_mm = options.cutter_distance_mm},
                           &out.joined_ring_points);
    out.rings_extended += extend_short_rings(
        b.boundary, region.ring_loops, {.min_length_mm = options.cutter_distance_mm, .step_mm = w});
    for (Polyline& c : chains) paths.push_back({PathRole::fibre, c.closed, std::move(c.points)});
    for (Polyline& r : b.boundary)
        paths.push_back({PathRole::fibre_boundary, r.closed, std::move(r.points)});
}

// A per-triangle value of the layer, on the triangles of one of its pieces.
std::vector<Eigen::Vector2d> on_piece(const LayerPiece& piece,
                                      const std::vector<Eigen::Vector2d>& of_layer) {
    std::vector<Eigen::Vector2d> out;
    out.reserve(piece.face_of_layer.size());
    for (int f : piece.face_of_layer) out.push_back(of_layer[f]);
    return out;
}

// The field strategy's curves on one piece: isocurves of the scalar field fitted to u_f, as
// many as W allows (Section 4.3).
std::vector<Polyline> piece_isocurves(const LayerPiece& piece, FibreLayer& out,
                                      const FibreLayerOptions& options) {
    Stopwatch clock;
    const std::vector<double> s = scalar_field(piece.mesh, on_piece(piece, out.field.u_f));
    out.timings.scalar_field += clock.lap();
    AdaptiveIsocurves curves = adaptive_isocurves(piece.mesh, s,
                                                  {.spacing_mm = options.spacing_mm,
                                                   .crowded_fraction = options.crowded_fraction,
                                                   .density_scale = options.density_scale});
    out.timings.extraction += clock.lap();
    spdlog::debug(
        "fibre.piece z={:.3f} triangles={} span={:.1f}mm curves={} extractions={} "
        "ruled_out={} min_distance={:.3f}mm",
        piece.mesh.z, piece.mesh.triangles.size(), curves.geodesic_span_mm, curves.count,
        curves.extractions, curves.counts_ruled_out, curves.min_distance_mm);
    if (curves.count == 0) return {};
    return std::move(curves.curves);
}

// The stripes' period by default, over W. Where the stress lines converge the stripes close up;
// the final laying cuts them back to W and the cutter drops what is left too short. On the Loop
// (Release, `fibrecell plan --strategy field-dense`): at 1.0 W 55.6 m kept of ~140 m of stripes
// (5,953 pieces dropped), at 1.1 W 76.3 m, at 1.2 W 80.3 m, at 1.4 W 75.3 m.
constexpr double stripe_period_over_w = 1.2;

// The field-dense strategy's curves on one piece: stripes along the smoothed stress directions
// v_f, one period apart.
std::vector<Polyline> piece_stripes(const LayerPiece& piece, FibreLayer& out,
                                    const FibreLayerOptions& options) {
    Stopwatch clock;
    const std::vector<Eigen::Vector2d> along = on_piece(piece, out.field.v_f);
    const double period =
        options.stripe_period_mm > 0 ? options.stripe_period_mm
                                     : stripe_period_over_w * options.spacing_mm;
    StripePattern stripes = stripe_pattern(piece.mesh, along, {.spacing_mm = period});
    out.timings.scalar_field += clock.lap();
    out.singular_triangles += stripes.singular_triangles;
    spdlog::debug("fibre.piece z={:.3f} triangles={} stripes={} singular={}", piece.mesh.z,
                  piece.mesh.triangles.size(), stripes.stripes.size(),
                  stripes.singular_triangles);
    return std::move(stripes.stripes);
}

}  // namespace

FibreLayer plan_fibre_layer(const LayerMesh& layer, const std::vector<Eigen::Vector3d>& v_e,
                            const std::vector<double>& sigma_e,
                            const std::vector<std::uint8_t>& v_defined,
                            const std::vector<std::array<int, 2>>& selected_edges,
                            const FibreLayerOptions& options) {
    FibreLayer out;
    Stopwatch clock;
    out.field = layer_field(layer, v_e, sigma_e, v_defined, options.field);
    out.timings.vector_field = clock.lap();

    std::vector<Toolpath> paths;
    for (const LayerPiece& piece : split_pieces(layer)) {
        const bool loaded = std::any_of(
            piece.mesh.triangle_tet.begin(), piece.mesh.triangle_tet.end(),
            [&](int tet) { return v_defined[tet] && sigma_e[tet] > options.min_tension; });
        if (!loaded) continue;
        std::vector<Polyline> curves = options.stripes ? piece_stripes(piece, out, options)
                                                       : piece_isocurves(piece, out, options);
        if (curves.empty()) continue;
        clock.lap();
        const FibreRegion region = fibre_region(
            layer_outline(piece.mesh), piece_selected(piece, selected_edges, layer.vertices.size()),
            {.spacing_mm = options.spacing_mm, .rings_at_edge = options.rings_at_edge});
        connect_piece(region, std::move(curves), options, out, paths);
        out.timings.connection += clock.lap();
    }
    // Every step above keeps W by its own rule; laying the paths once more, rings first and
    // then the longest first, makes it hold for the layer as a whole (a cut there is logged). The
    // cutter sits cutter_distance_mm behind the nozzle: a shorter piece cannot be laid and cut.
    std::vector<std::tuple<bool, double, std::size_t>> order;  // not a ring, -length, index
    for (std::size_t i = 0; i < paths.size(); ++i)
        order.emplace_back(paths[i].role != PathRole::fibre_boundary, -path_length(paths[i]), i);
    std::sort(order.begin(), order.end());
    LaidFibre laid(options.spacing_mm);
    std::vector<Toolpath> kept;
    for (const auto& [not_ring, minus_length, i] : order) {
        const Toolpath& p = paths[i];
        const double length = -minus_length;
        double laid_length = 0;
        for (LaidPiece& piece : laid.lay(p.points, p.closed, options.cutter_distance_mm)) {
            kept.push_back({p.role, piece.closed, std::move(piece.points)});
            laid_length += path_length(kept.back());
        }
        if (length >= options.cutter_distance_mm && laid_length < length - 1e-6) ++out.spacing_cuts;
    }
    // What the stripes and rings could not lay; the fill's pieces too short to lay are trials of
    // its own, not fibre the plan lost.
    out.dropped_short += laid.dropped_short();
    out.dropped_short_mm += laid.dropped_short_mm();
    if (options.stripes && options.gap_fill) {
        GapFill fill = fill_gaps(layer, out.field, kept, laid,
                                 {.spacing_mm = options.spacing_mm,
                                  .cutter_distance_mm = options.cutter_distance_mm});
        std::move(fill.paths.begin(), fill.paths.end(), std::back_inserter(kept));
    }
    paths = std::move(kept);
    if (out.spacing_cuts > 0)
        spdlog::debug("fibre.layer z={:.3f}: {} paths cut to keep W", layer.z, out.spacing_cuts);
    if (paths.empty())
        out.warnings.push_back("layer at z = " + std::to_string(layer.z) +
                               ": no fibre path (no usable tension, or every isocurve shorter "
                               "than the cutter distance)");
    clock.lap();
    out.paths = order_nearest(std::move(paths), Eigen::Vector2d::Zero());
    if (options.measure_spacing)
        out.min_spacing_mm = fibre_spacing_mm(out.paths, options.spacing_mm);
    out.timings.connection += clock.lap();
    return out;
}

}  // namespace fibrecell::planner
