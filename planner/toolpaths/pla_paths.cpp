#include "planner/toolpaths/pla_paths.hpp"

#include "planner/toolpaths/contour_fill.hpp"

#include <cmath>
#include <stdexcept>

namespace fibrecell::planner {

PlaPathOptions pla_path_options(const ProcessSpec& process) {
    PlaPathOptions options;
    options.line_width_mm = process.pla.line_width_mm;
    return options;
}

double pla_infill_angle_deg(int pla_layer, const PlaPathOptions& options) {
    return options.base_angle_deg + options.angle_step_deg * pla_layer;
}

std::vector<Toolpath> pla_layer_paths(const LayerOutline& outline, int pla_layer,
                                      const PlaPathOptions& options) {
    if (!(options.line_width_mm > 0) || !std::isfinite(options.line_width_mm))
        throw std::invalid_argument("PLA line_width_mm must be positive");
    if (options.perimeters < 0) throw std::invalid_argument("PLA perimeters must not be negative");
    ContourFillOptions fill;
    fill.pitch_mm = options.line_width_mm;
    fill.rings = options.perimeters;
    fill.angle_deg = pla_infill_angle_deg(pla_layer, options);
    fill.ring_role = PathRole::perimeter;
    fill.fill_role = PathRole::infill;
    fill.max_link_spacings = options.max_link_spacings;
    fill.arc_tolerance_mm = options.arc_tolerance_mm;
    fill.start_mm = options.start_mm;
    return contour_fill(outline, fill);
}

}  // namespace fibrecell::planner
