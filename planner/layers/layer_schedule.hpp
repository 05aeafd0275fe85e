#pragma once
// The layer stack of a job (job `layers`): PLA layers of equal height, each optionally topped by a
// thin CCF layer, in print order, with the model height at which each layer cuts the part.

#include "planner/job/job_spec.hpp"
#include "planner/toolpaths/toolpath.hpp"

#include <vector>

namespace fibrecell::planner {

struct ScheduledLayer {
    int index = 0;  // 0-based, in print order
    Head head = Head::pla;
    double thickness = 0;  // [mm]
    double z = 0;          // nozzle-tip height while it prints = top of the layer in the stack [mm]
    int pla_number = 1;    // 1-based PLA layer it is (pla) or sits on (ccf)
    double slice_z = 0;    // model height where the placed part is cut for this layer [mm]
};

// part_height_mm: H, the placed part's height. There are max(1, round(H / pla_h)) PLA layers and a
// CCF layer on top of each that spec.has_ccf_after() selects.
//
// slice_z maps the printed stack (height S, which differs from H by rounding and by the CCF
// layers) linearly onto the model, model = printed * H / S, so the stack covers [0, H] exactly:
// a PLA layer is cut at its mid-height, a CCF layer at the top of the PLA layer it sits on (where
// its fibres lie), kept a hair inside (0, H) so the plane never only grazes the part's top.
// Throws std::invalid_argument for a non-positive or non-finite height or layer height, or a stack
// of more than 100000 layers.
std::vector<ScheduledLayer> layer_schedule(double part_height_mm, const LayerScheduleSpec& spec);

}  // namespace fibrecell::planner
