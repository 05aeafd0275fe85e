#include "daemon/jobs/plan_job.hpp"

#include "daemon/print/plan_writer.hpp"
#include "daemon/sync/board_commands.hpp"
#include "planner/io/read_model.hpp"
#include "planner/io/vtk_writer.hpp"
#include "planner/plan/preview_svg.hpp"
#include "planner/plan/report.hpp"
#include "planner/plan/toolpaths_json.hpp"
#include "planner/stopwatch.hpp"

#include <spdlog/spdlog.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace fibrecell::daemon::jobs {
namespace {

void write_layer_outputs(print::PlanWriter& out, const planner::JobSpec& job,
                         const planner::LayerStageResult& layers) {
    out.write("toolpaths.json",
              planner::toolpaths_json_text(to_string(job.planner.strategy), layers.layers));
    // Fibre layers of the field strategy are drawn over their sigma map.
    std::vector<planner::TriangleScalars> maps(layers.layers.size());
    std::vector<const planner::TriangleScalars*> backgrounds(layers.layers.size(), nullptr);
    for (std::size_t i = 0; i < layers.layers.size(); ++i) {
        if (layers.sigma[i].empty()) continue;
        maps[i] = {&layers.sections[i], layers.sigma[i]};
        backgrounds[i] = &maps[i];
    }
    for (const auto& f : planner::preview_files(layers.layers, layers.outlines, backgrounds))
        out.write("preview/" + f.name, f.text);
}

// What the board will be told, for people reviewing the plan (print.json's "board").
nlohmann::json board_summary(const print::PrintSettings& s, const drivers::ExtruderConfig& x) {
    return {{"pla_tool", x.pla_tool},
            {"ccf_tool", x.ccf_tool},
            {"pla_temp_c", s.pla.temp_c},
            {"ccf_temp_c", s.ccf.temp_c},
            {"pla_e_per_path_mm",
             sync::pla_e_per_path_mm(x, s.pla.line_width_mm, s.pla.layer_height_mm)},
            {"thread_feed_mm", s.cutter_distance_mm}};
}

}  // namespace

PlanJobResult plan_job(const PlanRequest& request, const planner::StepControl& control,
                       const std::function<void(const planner::JobSpec&)>& on_loaded) {
    planner::Stopwatch clock;  // report.json's timings_s.total counts the job file too
    PlanJobResult r;
    r.job = planner::load_job_file(request.job_file.string());
    if (request.strategy) r.job.planner.strategy = *request.strategy;
    r.settings = print::print_settings(r.job, request.cell);
    std::filesystem::create_directories(request.out_dir);
    print::PlanWriter out(request.out_dir);
    if (on_loaded) on_loaded(r.job);

    control.report("read", 0.0);
    planner::Stopwatch read_clock;
    planner::VolumeModel model =
        planner::read_volume_model(r.job.model.mesh_path, r.job.model.stress_path);
    const double read_s = read_clock.elapsed();
    spdlog::info("plan.read {} vertices, {} tets from {} in {:.3f} s", model.mesh.vertex_count(),
                 model.mesh.tet_count(), r.job.model.mesh_path, read_s);
    control.check_cancel();

    r.field = planner::run_field_stage(r.job, std::move(model), control);
    r.field.timings.read = read_s;
    control.check_cancel();
    if (request.last_stage == PlanStage::layers) {
        r.layers = planner::run_layer_stage(
            r.job, r.field,
            {.cutter_distance_mm = r.settings.cutter_distance_mm, .executor = request.executor},
            control);
        control.check_cancel();
    }
    control.report("write", 0.0);
    out.write("field.vtk", planner::field_vtk_text(r.field.model.mesh,
                                                   {&*r.field.model.stress, &r.field.field.sigma_e,
                                                    &r.field.field.v_e, &r.field.v_defined}));
    r.report = planner::field_stage_report(r.job, r.field);
    if (r.layers) {
        write_layer_outputs(out, r.job, *r.layers);
        planner::add_layer_stage_report(r.report, *r.layers);
        control.check_cancel();
        control.report("robot", 0.0);
        r.robot = print::plan_robot(r.layers->layers, request.cell.robot, r.settings, r.job.name);
        // A plan that would print nothing is a mistake in the job, not a plan.
        if (r.robot->program.events.empty())
            throw std::runtime_error(
                "nothing to print: none of the " + std::to_string(r.layers->layers.size()) +
                " layers has a toolpath (is the part smaller than the nozzle's line, or "
                "placed outside the bed?)");
        print::add_robot_report(r.report, *r.robot);
        print::write_print_files(
            out, *r.robot,
            {.job = r.job.name,
             .strategy = std::string(to_string(r.job.planner.strategy)),
             .layers = r.layers->layers.size(),
             .settings = r.settings,
             .board = board_summary(r.settings, request.cell.extruder)});
    }
    control.check_cancel();
    r.report["settings"] = print::to_json(r.settings);
    r.report["timings_s"]["total"] = clock.elapsed();
    out.write("report.json", r.report.dump(2) + "\n");
    out.finish(r.job.name, print::cell_facts(request.cell));
    return r;
}

}  // namespace fibrecell::daemon::jobs
