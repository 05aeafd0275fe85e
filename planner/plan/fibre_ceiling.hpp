#pragma once
// The most a plan's fibre could buy on a part: every CCF layer's section laid full at spacing W,
// each bit of fibre along the principal tensile direction of the tet it lies in (the field
// stage's v_e). No real path can do this (paths have to be continuous, keep W from each other and
// turn where the field turns), so its predicted stiffness is the ceiling a plan is measured
// against: how much of the possible gain the plan takes (`fibrecell compare`).

#include "planner/job/job_spec.hpp"
#include "planner/plan/field_stage.hpp"
#include "planner/plan/layer_stage.hpp"

namespace fibrecell::planner {

// `layers` with each CCF layer's paths replaced by the ideal fibre: per section triangle whose
// tet has a defined direction, area / W of fibre along that direction in straight pieces through
// its centroid, each short enough to stay inside the triangle (so the section gets fibre
// length x W = its area, all of it in the tets it belongs to). PLA layers as they are.
LayerStageResult ideal_fibre_layers(const JobSpec& job, const FieldStageResult& field,
                                    const LayerStageResult& layers);

}  // namespace fibrecell::planner
