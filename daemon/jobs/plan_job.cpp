#include "daemon/jobs/plan_job.hpp"

#include "planner/io/vtk_writer.hpp"
#include "planner/plan/preview_svg.hpp"
#include "planner/plan/report.hpp"
#include "planner/plan/toolpaths_json.hpp"
#include "planner/stopwatch.hpp"

#include <vector>

namespace fibrecell::daemon::jobs {
namespace {

void write_layer_outputs(const std::filesystem::path& out, const planner::JobSpec& job,
                         const planner::LayerStageResult& layers) {
    planner::write_toolpaths_json((out / "toolpaths.json").string(),
                                  to_string(job.planner.strategy), layers.layers);
    // Fibre layers of the field strategy are drawn over their sigma map.
    std::vector<planner::TriangleScalars> maps(layers.layers.size());
    std::vector<const planner::TriangleScalars*> backgrounds(layers.layers.size(), nullptr);
    for (std::size_t i = 0; i < layers.layers.size(); ++i) {
        if (layers.sigma[i].empty()) continue;
        maps[i] = {&layers.sections[i], layers.sigma[i]};
        backgrounds[i] = &maps[i];
    }
    planner::write_preview((out / "preview").string(), layers.layers, layers.outlines, backgrounds);
}

}  // namespace

PlanJobResult plan_job(const PlanRequest& request, const planner::StepControl& control,
                       const std::function<void(const planner::JobSpec&)>& on_loaded) {
    planner::Stopwatch clock;  // report.json's timings_s.total counts the job file too
    PlanJobResult r;
    r.job = planner::load_job_file(request.job_file.string());
    if (request.strategy) r.job.planner.strategy = *request.strategy;
    std::filesystem::create_directories(request.out_dir);
    if (on_loaded) on_loaded(r.job);

    const std::filesystem::path& out = request.out_dir;
    r.field = planner::run_field_stage(r.job, control);
    control.check_cancel();
    if (request.last_stage == PlanStage::layers) {
        r.layers = planner::run_layer_stage(r.job, r.field, request.threads, control);
        control.check_cancel();
    }
    control.report("write", 0.0);
    planner::write_field_vtk(
        (out / "field.vtk").string(), r.field.model.mesh,
        {&*r.field.model.stress, &r.field.field.sigma_e, &r.field.field.v_e, &r.field.v_defined});
    r.report = planner::field_stage_report(r.job, r.field);
    if (r.layers) {
        write_layer_outputs(out, r.job, *r.layers);
        planner::add_layer_stage_report(r.report, *r.layers);
        control.check_cancel();
        control.report("robot", 0.0);
        r.robot = plan_robot(r.job, r.layers->layers, request.robot, out / "rapid");
        add_robot_report(r.report, *r.robot);
    }
    control.check_cancel();
    r.report["timings_s"]["total"] = clock.elapsed();
    // report.json last: its presence marks a complete plan directory.
    planner::write_json_file((out / "report.json").string(), r.report);
    return r;
}

}  // namespace fibrecell::daemon::jobs
