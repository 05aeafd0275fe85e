#pragma once
// Field-based fibre paths of one CCF layer (paper Sections 4.2-4.4): the in-plane field, the
// scalar field per piece, adaptive isocurves, boundary-conformal rings and the connection of
// curves into continuous paths, and the cutter's minimum length.

#include "planner/fibre/layer_field.hpp"
#include "planner/layers/layer_mesh.hpp"
#include "planner/toolpaths/toolpath.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace fibrecell::planner {

struct FibreLayerOptions {
    LayerFieldOptions field;                               // smoothing iterations, p
    double spacing_mm = 1.0;                               // W
    double crowded_fraction = 0;                           // see AdaptiveIsocurveOptions
    double density_scale = 1;                              // see AdaptiveIsocurveOptions
    double cutter_distance_mm = paper_cutter_distance_mm;  // shorter fibre paths cannot be laid
    // A piece none of whose tets carries more tension than this gets no fibres: isovalues are
    // relative to the piece's own range, so without this a piece with only the rule-3 marker
    // (sigma_e = 1e-5) would be filled like a loaded one.
    double min_tension = 1e-4;
    // The field-dense strategy: stripes along the field every `stripe_period_mm` instead of the
    // scalar field's isocurves; the connection and the W rule are the same.
    bool stripes = false;
    double stripe_period_mm = 0;  // 0: the default, 1.2 W (fibre_layer.cpp)
    // Then fill what the stripes left bare (gap_fill.hpp); off under a fibre budget, which sets
    // the fibre by the stripes' period.
    bool gap_fill = true;
    bool rings_at_edge = false;  // FibreRegionOptions::rings_at_edge (field-dense: true)
    // FibreLayer::min_spacing_mm. Off where a caller tries several densities and keeps one (a
    // fibre budget: about six tries a layer), measuring the one it keeps.
    bool measure_spacing = true;
};

struct FibreLayerTimings {  // seconds, the paper's Table 1 columns
    double vector_field = 0;
    double scalar_field = 0;
    double extraction = 0;
    double connection = 0;
};

struct FibreLayer {
    std::vector<Toolpath> paths;     // roles fibre and fibre-boundary, in print order
    LayerField field;                // per triangle of the layer (for previews)
    std::size_t dropped_short = 0;   // paths shorter than the cutter distance (not the fill's trials)
    double dropped_short_mm = 0;     // their length
    std::size_t joins = 0;           // links made by the connection (Steps 3-4)
    std::size_t spacing_cuts = 0;    // paths the final laying had to cut to keep W
    std::size_t rings_joined = 0;    // rings shorter than the cutter laid as part of a stress path
    std::size_t rings_extended = 0;  // arcs too short to cut run on along their loop instead
    std::size_t singular_triangles = 0;  // field-dense: where the stripes branch (none cross)
    // Where they are, for the report per boundary: each link's meeting point (the middle of the
    // two ends it joins) and the first point of each joined ring.
    std::vector<Eigen::Vector2d> join_points, joined_ring_points;
    // Smallest distance between two different paths, capped at 3W (0: fewer than two paths, or
    // not measured).
    double min_spacing_mm = 0;
    std::vector<std::string> warnings;  // e.g. "no tension in this layer"
    FibreLayerTimings timings;
};

// v_e, sigma_e, v_defined: per tet, v_e in the frame of `layer` (placed). selected_edges: the
// outline edges of `layer` (vertex pairs) on the boundary chosen for boundary-conformal fibres
// (may be empty). Every fibre keeps W/2 inside the layer's outline.
FibreLayer plan_fibre_layer(const LayerMesh& layer, const std::vector<Eigen::Vector3d>& v_e,
                            const std::vector<double>& sigma_e,
                            const std::vector<std::uint8_t>& v_defined,
                            const std::vector<std::array<int, 2>>& selected_edges,
                            const FibreLayerOptions& options = {});

}  // namespace fibrecell::planner
