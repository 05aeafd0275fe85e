#include "planner/toolpaths/contour_zigzag.hpp"

#include "planner/fibre/laid_fibre.hpp"
#include "planner/toolpaths/contour_fill.hpp"

#include <cmath>
#include <stdexcept>

namespace fibrecell::planner {

ContourZigzagOptions contour_zigzag_options(const PlannerSpec& planner, double cutter_distance_mm) {
    ContourZigzagOptions options;
    options.fibre_spacing_mm = planner.fibre_spacing_mm;
    options.cutter_distance_mm = cutter_distance_mm;
    return options;
}

double contour_zigzag_angle_deg(int ccf_layer, const ContourZigzagOptions& options) {
    return options.base_angle_deg + options.angle_step_deg * ccf_layer;
}

FibreLayerPaths contour_zigzag_paths(const LayerOutline& outline, int ccf_layer,
                                     const ContourZigzagOptions& options) {
    if (!(options.cutter_distance_mm >= 0) || !std::isfinite(options.cutter_distance_mm))
        throw std::invalid_argument("contour-zigzag cutter_distance_mm must not be negative");
    if (!(options.fibre_spacing_mm > 0) || !std::isfinite(options.fibre_spacing_mm))
        throw std::invalid_argument("contour-zigzag fibre_spacing_mm (W) must be positive");
    if (options.boundary_rings < 0)
        throw std::invalid_argument("contour-zigzag boundary_rings must not be negative");
    ContourFillOptions fill;
    fill.pitch_mm = options.fibre_spacing_mm;
    fill.rings = options.boundary_rings;
    fill.fill_spacing_mm = options.zigzag_spacing_mm;
    fill.angle_deg = contour_zigzag_angle_deg(ccf_layer, options);
    fill.ring_role = PathRole::fibre_boundary;
    fill.fill_role = PathRole::fibre;
    fill.ribbons_overlap = false;
    fill.max_link_spacings = options.max_link_spacings;
    fill.arc_tolerance_mm = options.arc_tolerance_mm;
    fill.start_mm = options.start_mm;

    // Rings and zigzag keep W from each other by their insets; laying them in print order cuts
    // what still crowds (zigzag stubs where a scan line grazes the boundary, rings across a neck
    // narrower than their pitch allows).
    FibreLayerPaths result;
    LaidFibre laid(options.fibre_spacing_mm);
    for (const Toolpath& path : contour_fill(outline, fill))
        for (LaidPiece& piece : laid.lay(path.points, path.closed, options.cutter_distance_mm))
            result.paths.push_back({path.role, piece.closed, std::move(piece.points)});
    result.dropped_short = laid.dropped_short();
    result.dropped_short_mm = laid.dropped_short_mm();
    return result;
}

}  // namespace fibrecell::planner
