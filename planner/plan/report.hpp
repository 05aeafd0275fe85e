#pragma once
// report.json of the plan directory (format fibrecell.report/1, keys in docs/contracts.md).

#include "planner/job/job_spec.hpp"
#include "planner/plan/field_stage.hpp"
#include "planner/plan/layer_stage.hpp"
#include "planner/plan/mechanics_stage.hpp"
#include "planner/plan/parameter_sweep.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace fibrecell::planner {

// The report of a plan that ran the field stage: model.*, fea.*, field.* and timings_s.*.
nlohmann::json field_stage_report(const JobSpec& job, const FieldStageResult& result);

// Adds the layer stage: layers.*, fibre.*, pla.*, timings_s.layers and timings_s.per_layer_mean.
void add_layer_stage_report(nlohmann::json& report, const LayerStageResult& layers);

// Adds sweep.parameter and sweep.points (one per value, in the sweep's order).
void add_sweep_report(nlohmann::json& report, const ParameterSweep& sweep);

// Adds mechanics.* (the predicted stiffness, bare and reinforced) and timings_s.mechanics.
void add_mechanics_report(nlohmann::json& report, const MechanicsResult& mechanics);

}  // namespace fibrecell::planner
