#include "daemon/jobs/plan_job.hpp"

#include "daemon/print/part_fit.hpp"
#include "daemon/print/plan_writer.hpp"
#include "daemon/sync/board_commands.hpp"
#include "planner/io/read_model.hpp"
#include "planner/io/vtk_writer.hpp"
#include "planner/plan/analysis_svg.hpp"
#include "planner/plan/preview_svg.hpp"
#include "planner/plan/report.hpp"
#include "planner/plan/toolpaths_json.hpp"
#include "planner/stopwatch.hpp"

#include <spdlog/spdlog.h>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace fibrecell::daemon::jobs {
namespace {

// The PLA's von Mises stress with the fibre in, on the middle CCF layer (its fibre drawn over
// it): where the reinforced part is still loaded.
planner::PreviewFigure reinforced_stress_figure(const planner::LayerStageResult& layers,
                                                const planner::MechanicsResult& m) {
    std::vector<std::size_t> ccf;
    for (std::size_t i = 0; i < layers.layers.size(); ++i)
        if (layers.layers[i].head == planner::Head::ccf) ccf.push_back(i);
    if (ccf.empty()) ccf.push_back(layers.layers.size() / 2);
    const std::size_t i = ccf[ccf.size() / 2];
    const planner::LayerMesh& section = layers.sections[i];
    std::vector<double> stress(section.triangles.size());
    for (std::size_t f = 0; f < stress.size(); ++f)
        stress[f] = m.prediction.reinforced_von_mises[section.triangle_tet[f]];
    const planner::TriangleScalars map{&section, stress};
    char caption[200];
    std::snprintf(caption, sizeof caption,
                  "PLA von Mises stress with the fibre, layer %zu (dark: low, yellow: high; "
                  "peak %.1f MPa, bare %.1f MPa); predicted stiffness %.2fx the bare part's",
                  i, m.prediction.reinforced.von_mises_peak_mpa,
                  m.prediction.bare.von_mises_peak_mpa, m.prediction.gain());
    return {
        {"reinforced_stress.svg", planner::layer_svg(layers.layers[i], &layers.outlines[i], &map)},
        caption};
}

// The paper's analyses beside the layers: Fig. 8 always, Fig. 9 when a sweep ran.
std::vector<planner::PreviewFigure> analysis_figures(const PlanJobResult& r) {
    std::vector<planner::PreviewFigure> figures;
    figures.push_back({{"neighbour_dots.svg",
                        planner::neighbour_dots_svg(r.field.neighbour_dots, r.job.planner.eta)},
                       std::string("Dot products of neighbouring directions ") +
                           (r.job.planner.mst_reorientation ? "after the MST re-orientation"
                                                            : "without the MST re-orientation") +
                           " (paper Fig. 8)"});
    if (r.sweep)
        figures.push_back({{"sweep.svg", planner::sweep_svg(*r.sweep)},
                           "Fibre length against " + r.sweep->parameter + " (paper Fig. 9)"});
    if (r.mechanics) figures.push_back(reinforced_stress_figure(*r.layers, *r.mechanics));
    return figures;
}

void write_layer_outputs(print::PlanWriter& out, const PlanJobResult& r) {
    const planner::JobSpec& job = r.job;
    const planner::LayerStageResult& layers = *r.layers;
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
    // Every fibre path also as the W-wide ribbon it lays: the gaps are what it leaves uncovered.
    for (const auto& f : planner::preview_files(layers.layers, layers.outlines, backgrounds,
                                                {.ribbon_mm = job.planner.fibre_spacing_mm},
                                                analysis_figures(r)))
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
    r.job = request.job ? *request.job : planner::load_job_file(request.job_file.string());
    if (request.strategy) r.job.planner.strategy = *request.strategy;
    if (request.fibre_budget) r.job.planner.fibre_budget = *request.fibre_budget;
    r.settings = request.settings ? *request.settings : print::print_settings(r.job, request.cell);
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
    // Before any work that grows with the part's size (docs/service.md, "Size limits").
    print::check_part_fits_cell(model.mesh, r.job, request.cell);

    r.field = planner::run_field_stage(r.job, std::move(model), control);
    r.field.timings.read = read_s;
    control.check_cancel();
    if (request.last_stage == PlanStage::layers) {
        const planner::LayerStageOptions options{
            .cutter_distance_mm = r.settings.cutter_distance_mm, .executor = request.executor};
        r.layers = planner::run_layer_stage(r.job, r.field, options, control);
        control.check_cancel();
        if (request.sweep) {
            r.sweep = request.sweep;
            planner::run_sweep(*r.sweep, r.job, r.field, options, control);
        }
        if (request.mechanics && planner::wants_mechanics(r.job)) {
            r.mechanics = planner::run_mechanics_stage(r.job, r.field, *r.layers, control);
            control.check_cancel();
        }
    }
    control.report("write", 0.0);
    out.write("field.vtk", planner::field_vtk_text(r.field.model.mesh,
                                                   {&*r.field.model.stress, &r.field.field.sigma_e,
                                                    &r.field.field.v_e, &r.field.v_defined}));
    r.report = planner::field_stage_report(r.job, r.field);
    if (r.layers) {
        write_layer_outputs(out, r);
        planner::add_layer_stage_report(r.report, *r.layers);
        if (r.sweep) planner::add_sweep_report(r.report, *r.sweep);
        if (r.mechanics) planner::add_mechanics_report(r.report, *r.mechanics);
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
        print::write_print_files(out, *r.robot,
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
