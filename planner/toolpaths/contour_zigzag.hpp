#pragma once
// The load-independent baseline fibre strategy `contour-zigzag` (docs/job-format.md, "What a
// print is"): boundary-conformal fibre rings plus a zigzag fibre fill, as commercial fibre
// slicers do; paths shorter than the cutter distance cannot be laid and are dropped.

#include "planner/job/job_spec.hpp"
#include "planner/layers/layer_mesh.hpp"
#include "planner/toolpaths/toolpath.hpp"

#include <vector>

namespace fibrecell::planner {

struct ContourZigzagOptions {
    double fibre_spacing_mm = 1.0;  // W: ring pitch and zigzag spacing
    double zigzag_spacing_mm = 0;   // a sparser zigzag (to meet a fibre budget); 0: W
    int boundary_rings = 2;         // fibre-boundary rings per island
    double base_angle_deg = 0;      // zigzag direction of CCF layer 0, ccw from +x
    double angle_step_deg = 45;     // turn of the zigzag direction per CCF layer
    double cutter_distance_mm = paper_cutter_distance_mm;  // shorter paths are dropped
    double max_link_spacings = 4;     // longest boundary link in the zigzag [W]
    double arc_tolerance_mm = 0.002;  // round joins of the offsets
    Eigen::Vector2d start_mm{0, 0};   // nozzle before the layer: ordering starts here
};

// The options a job asks for (planner.fibre_spacing_mm) on a head whose cutter sits
// `cutter_distance_mm` before the nozzle tip.
ContourZigzagOptions contour_zigzag_options(const PlannerSpec& planner, double cutter_distance_mm);

// Zigzag direction [deg] of CCF layer `ccf_layer` (0-based count of CCF layers).
double contour_zigzag_angle_deg(int ccf_layer, const ContourZigzagOptions& options);

struct FibreLayerPaths {
    std::vector<Toolpath> paths;  // print order
    int dropped_short = 0;        // paths or pieces shorter than the cutter distance, left out
    double dropped_short_mm = 0;  // their length
};

// `outline` [mm] of the layer. Per island: fibre-boundary rings (closed) at W/2 + i*W inside the
// outline (plus the round joins' chord margin, see ContourFillOptions::ribbons_overlap), then fibre
// zigzag paths (open) at spacing W over the outline inset by boundary_rings*W + W/2 (so no zigzag
// point comes within W of a ring); then each path, in print order, laid as LaidFibre::lay does
// (cut where it still comes within W of fibre laid before it or of itself), pieces shorter than
// cutter_distance_mm dropped and counted. Throws std::invalid_argument on a non-positive spacing,
// negative rings or cutter distance, or a bad outline.
FibreLayerPaths contour_zigzag_paths(const LayerOutline& outline, int ccf_layer,
                                     const ContourZigzagOptions& options = {});

}  // namespace fibrecell::planner
