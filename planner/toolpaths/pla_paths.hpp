#pragma once
// Toolpaths of a PLA matrix layer: perimeters plus a zigzag infill whose direction turns from one
// PLA layer to the next (docs/job-format.md, "What a print is").

#include "planner/job/job_spec.hpp"
#include "planner/layers/layer_mesh.hpp"
#include "planner/toolpaths/toolpath.hpp"

#include <vector>

namespace fibrecell::planner {

struct PlaPathOptions {
    double line_width_mm = 0.8;       // w: bead width, perimeter pitch and infill spacing
    int perimeters = 2;               // rings per island before the infill
    double base_angle_deg = 0;        // infill direction of PLA layer 0, ccw from +x
    double angle_step_deg = 45;       // turn of the infill direction per PLA layer
    double max_link_spacings = 4;     // longest boundary link in the zigzag [line widths]
    double arc_tolerance_mm = 0.002;  // round joins of the offsets
    Eigen::Vector2d start_mm{0, 0};   // nozzle before the layer: ordering starts here
};

// The options a job asks for (process.pla.line_width_mm); the rest keep their defaults.
PlaPathOptions pla_path_options(const ProcessSpec& process);

// Infill direction [deg] of PLA layer `pla_layer` (0-based count of PLA layers): base + step * n.
double pla_infill_angle_deg(int pla_layer, const PlaPathOptions& options);

// `outline` [mm] of the layer. Returns, per island in nearest-first order, perimeter rings
// (closed) at w/2 + i*w inside the outline, then infill (open zigzag paths) at spacing w over the
// outline inset by perimeters*w (see contour_fill_inset_mm): every infill point lies at least
// perimeters*w (w/2 without perimeters) from the outline, up to arc_tolerance_mm. Throws
// std::invalid_argument on a non-positive line width, negative perimeters or a bad outline.
std::vector<Toolpath> pla_layer_paths(const LayerOutline& outline, int pla_layer,
                                      const PlaPathOptions& options = {});

}  // namespace fibrecell::planner
