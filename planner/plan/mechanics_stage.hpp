#pragma once
// The last planning stage: what the plan's fibres buy. The job's load case is solved for the
// bare part and again with the CCF of the layer stage smeared into the tets it crosses
// (planner/mechanics, docs/mechanics.md).

#include "planner/job/job_spec.hpp"
#include "planner/mechanics/reinforced_material.hpp"
#include "planner/mechanics/stiffness_prediction.hpp"
#include "planner/plan/field_stage.hpp"
#include "planner/plan/layer_stage.hpp"
#include "planner/progress.hpp"

#include <optional>

namespace fibrecell::planner {

struct MechanicsResult {
    FibreMaterial fibre;            // as the job gave it
    double fibre_placed_mm = 0;     // CCF located in the model's tets
    double fibre_unplaced_mm = 0;   // CCF off every section triangle
    double fibre_volume_mm3 = 0;    // fibre (not ribbon) volume in the part
    double max_fibre_fraction = 0;  // the largest v_f of a tet
    int reinforced_tets = 0, saturated_tets = 0;
    StiffnessPrediction prediction;  // bare and reinforced
    double locate_s = 0;             // fibre located in the tets, material made
    double seconds = 0;              // the whole stage
};

// Whether the job gets the analysis: enabled and a load case known (model or analysis section).
bool wants_mechanics(const JobSpec& job);

// Throws std::invalid_argument (wants_mechanics false, regions that fit no boundary), FeaError,
// Cancelled. Progress: ("mechanics", fraction).
MechanicsResult run_mechanics_stage(const JobSpec& job, const FieldStageResult& field,
                                    const LayerStageResult& layers,
                                    const StepControl& control = {});

}  // namespace fibrecell::planner
