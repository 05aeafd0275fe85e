#pragma once
// The one way a job is planned: read the job YAML, make the print's settings for the cell (or
// refuse the job), read the model, run the planner's stages and write the plan directory
// (docs/contracts.md): field.vtk, toolpaths.json, preview/, report.json and the print itself —
// rapid/, program.json, print.json — with manifest.json last (daemon/print/plan_writer.hpp). The
// offline `fibrecell plan` and the service's planning workers both call plan_job.
//
//   PlanRequest r{.job_file = "loop.job.yaml", .out_dir = "plan", .cell = cell};
//   PlanJobResult p = plan_job(r, {progress_sink, &cancel_token});

#include "daemon/cell/cell_config.hpp"
#include "daemon/print/print_settings.hpp"
#include "daemon/print/robot_plan.hpp"
#include "planner/executor.hpp"
#include "planner/job/job_spec.hpp"
#include "planner/plan/field_stage.hpp"
#include "planner/plan/layer_stage.hpp"
#include "planner/plan/mechanics_stage.hpp"
#include "planner/plan/parameter_sweep.hpp"
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
    // The job as its submission read it (the service's store), instead of reading job_file, and
    // the print's settings made then, instead of making them again.
    std::optional<planner::JobSpec> job;
    std::optional<print::PrintSettings> settings;
    std::filesystem::path out_dir;              // the plan directory (created)
    PlanStage last_stage = PlanStage::layers;   // layers: toolpaths, preview, the print too
    std::optional<planner::Strategy> strategy;  // overrides the job's planner.strategy
    std::optional<planner::FibreBudget> fibre_budget;  // overrides planner.fibre_budget
    CellConfig cell;                                   // the cell that will print it
    planner::Executor* executor = nullptr;  // runs the layers; null: on the calling thread
    // Plans the layers again at each of these values (report.json's sweep, preview/sweep.svg);
    // the plan itself stays the job's own.
    std::optional<planner::ParameterSweep> sweep;
    // Predicts the stiffness (report.json's mechanics) when the job has a load case and its
    // analysis is enabled; false skips it whatever the job says.
    bool mechanics = true;
};

struct PlanJobResult {
    planner::JobSpec job;  // as planned (strategy and budget overrides applied)
    print::PrintSettings settings;
    planner::FieldStageResult field;
    std::optional<planner::LayerStageResult> layers;    // when last_stage == layers
    std::optional<print::RobotPlan> robot;              // when last_stage == layers
    std::optional<planner::ParameterSweep> sweep;       // when asked for, with its points
    std::optional<planner::MechanicsResult> mechanics;  // when the job gets the analysis
    nlohmann::json report;                              // as written to report.json
};

// Progress goes to `control.progress` per stage ("read", the planner's stage names, "sweep" when
// asked for, "mechanics" when the job has a load case, then "write" and "robot"), from the calling
// thread or, for "layers", from the executor's threads one call at a time; `control.cancel` is
// checked between stages and inside the long ones. `on_loaded` runs once the job file is read and
// its settings made (the CLI names the job there). Throws config::ConfigError (job file),
// print::SettingsError (a setting the cell cannot print), planner::InputError / FeaError (model),
// PrintProgramError / RapidWriteError (robot), planner::Cancelled, std::system_error (files). A
// plan directory without manifest.json is incomplete: callers must not present it.
PlanJobResult plan_job(const PlanRequest& request, const planner::StepControl& control = {},
                       const std::function<void(const planner::JobSpec&)>& on_loaded = {});

}  // namespace fibrecell::daemon::jobs
