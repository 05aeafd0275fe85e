#pragma once
// The one way a job is planned: read the job YAML, run the planner's stages and write the plan
// directory of docs/contracts.md (field.vtk, toolpaths.json, preview/, rapid/, report.json). The
// offline `fibrecell plan` and the service's planning workers both call plan_job.
//
//   PlanRequest r{.job_file = "loop.job.yaml", .out_dir = "plan"};
//   PlanJobResult p = plan_job(r, {progress_sink, &cancel_token});

#include "daemon/robot_plan.hpp"
#include "drivers/abb/cell/robot_config.hpp"
#include "planner/job/job_spec.hpp"
#include "planner/plan/field_stage.hpp"
#include "planner/plan/layer_stage.hpp"
#include "planner/progress.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <optional>

namespace fibrecell::daemon::jobs {

// How far planning goes: the 3D field only (field.vtk + report.json) or everything.
enum class PlanStage { field, layers };

struct PlanRequest {
    std::filesystem::path job_file;             // the job YAML; relative paths resolve beside it
    std::filesystem::path out_dir;              // the plan directory (created)
    PlanStage last_stage = PlanStage::layers;   // layers: toolpaths, preview, RAPID too
    std::optional<planner::Strategy> strategy;  // overrides the job's planner.strategy
    int threads = 0;                            // layer workers (0 = hardware concurrency)
    drivers::abb::RobotCellConfig robot;        // the cell the RAPID program is for
};

struct PlanJobResult {
    planner::JobSpec job;  // as planned (strategy override applied)
    planner::FieldStageResult field;
    std::optional<planner::LayerStageResult> layers;  // when last_stage == layers
    std::optional<RobotPlan> robot;                   // when last_stage == layers
    nlohmann::json report;                            // as written to report.json
};

// Progress goes to `control.progress` per stage (the planner's stage names, then "write" and
// "robot"); `control.cancel` is checked between stages and inside the long ones. `on_loaded`
// runs once the job file is read and the plan directory created (the CLI names the job there).
// Throws config::ConfigError (job file), planner::InputError / FeaError (model),
// PrintProgramError / RapidWriteError (robot), planner::Cancelled, std::runtime_error (files);
// the plan directory may then hold partial output: callers must not present it.
PlanJobResult plan_job(const PlanRequest& request, const planner::StepControl& control = {},
                       const std::function<void(const planner::JobSpec&)>& on_loaded = {});

}  // namespace fibrecell::daemon::jobs
