#include "tools/fibrecell/plan_command.hpp"

#include "daemon/cell_config.hpp"
#include "daemon/robot_plan.hpp"
#include "planner/io/vtk_writer.hpp"
#include "planner/job/job_spec.hpp"
#include "planner/plan/field_stage.hpp"
#include "planner/plan/layer_stage.hpp"
#include "planner/plan/preview_svg.hpp"
#include "planner/plan/report.hpp"
#include "planner/plan/toolpaths_json.hpp"
#include "planner/stopwatch.hpp"
#include "tools/fibrecell/console_progress.hpp"

#include <spdlog/spdlog.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

namespace fibrecell::tools {
namespace {

struct PlanArgs {
    std::string job;
    std::string out;
    std::string stage = "layers";
    std::string strategy;
    std::string cell;  // cell YAML; empty: the simulated cell's defaults
    int threads = 0;
};

void print_summary(const planner::FieldStageResult& r, const std::string& out) {
    const auto& t = r.timings;
    const double n = static_cast<double>(r.v_defined.size());
    std::printf("model      %zu tets, %zu vertices\n", r.model.mesh.tet_count(),
                r.model.mesh.vertex_count());
    if (r.fea)
        std::printf(
            "fea        %zu unknowns (%s), max displacement %.4f mm, reactions %.1f N "
            "against %.1f N applied\n",
            r.fea->dof_count, r.fea->solver.c_str(), r.fea->max_displacement_mm,
            r.fea->reaction_sum_n.norm(), r.fea->applied_sum_n.norm());
    const auto& by_rule = r.removed_fraction_by_rule;  // indexed by IncompatibilityRule
    std::printf(
        "field      %d component(s), %d vectors flipped by the MST, %zu undefined (%.2f%%; "
        "Eq. 2 read as all/majority/any: %.2f%%/%.2f%%/%.2f%%)\n",
        r.mst.components, r.mst.flipped, r.removed, 100.0 * static_cast<double>(r.removed) / n,
        100.0 * by_rule[0], 100.0 * by_rule[2], 100.0 * by_rule[1]);
    std::printf(
        "timings    read %.3f s, fea %.3f s, principal %.3f s, mst %.3f s, removal %.3f s, "
        "total %.3f s\n",
        t.read, t.fea, t.principal, t.mst_reorientation, t.incompatible_removal, t.total);
    std::printf("wrote      %s/field.vtk, %s/report.json\n", out.c_str(), out.c_str());
}

void write_layer_outputs(const std::string& out, const planner::JobSpec& job,
                         const planner::LayerStageResult& layers) {
    planner::write_toolpaths_json(out + "/toolpaths.json", to_string(job.planner.strategy),
                                  layers.layers);
    // Fibre layers of the field strategy are drawn over their sigma map.
    std::vector<planner::TriangleScalars> maps(layers.layers.size());
    std::vector<const planner::TriangleScalars*> backgrounds(layers.layers.size(), nullptr);
    for (std::size_t i = 0; i < layers.layers.size(); ++i) {
        if (layers.sigma[i].empty()) continue;
        maps[i] = {&layers.sections[i], layers.sigma[i]};
        backgrounds[i] = &maps[i];
    }
    planner::write_preview(out + "/preview", layers.layers, layers.outlines, backgrounds);
}

void print_robot_summary(const daemon::RobotPlan& plan, const std::string& out) {
    const auto& s = plan.program.stats;
    std::printf(
        "robot      %zu moves, %zu events (%zu barriers), %zu head switches, about %.0f min of "
        "printing; %zu RAPID modules (%zu lines) in %.3f s\n",
        s.moves, s.events, s.barriers, s.head_switches, s.duration_s / 60.0, plan.rapid.modules,
        plan.rapid.lines, plan.seconds);
    std::printf("wrote      %s/rapid/\n", out.c_str());
}

void print_layer_summary(const planner::LayerStageResult& layers, const std::string& out) {
    const auto& s = layers.stats;
    std::printf(
        "layers     %d PLA + %d CCF in %.3f s (per CCF layer: field %.3f s, scalar %.3f s, "
        "extraction %.3f s)\n",
        s.pla_layers, s.ccf_layers, s.total_s, s.mean_vector_field, s.mean_scalar_field,
        s.mean_extraction);
    std::printf(
        "fibre      %.2f m in %d paths (min spacing %.3f mm, shortest %.1f mm, %d dropped "
        "as too short); PLA %.2f m\n",
        s.fibre_length_mm / 1000.0, s.fibre_paths, s.fibre_min_spacing_mm, s.fibre_min_length_mm,
        s.dropped_short, s.pla_length_mm / 1000.0);
    std::printf(
        "quality    fibres along the tension: stress-weighted |cos| %.3f; density vs "
        "sigma^p correlation %.3f\n",
        s.quality.alignment(), s.quality.density_correlation());
    for (const auto& w : layers.warnings) std::printf("warning    %s\n", w.c_str());
    std::printf("wrote      %s/toolpaths.json, %s/preview/index.html\n", out.c_str(), out.c_str());
}

int run_plan(const PlanArgs& args) {
    planner::Stopwatch clock;
    try {
        planner::JobSpec job = planner::load_job_file(args.job);
        const drivers::abb::RobotCellConfig robot = args.cell.empty()
                                                        ? drivers::abb::RobotCellConfig{}
                                                        : daemon::load_cell_config(args.cell).robot;
        if (!args.strategy.empty())
            job.planner.strategy = args.strategy == "field" ? planner::Strategy::field
                                                            : planner::Strategy::contour_zigzag;
        std::filesystem::create_directories(args.out);
        std::fprintf(stderr, "planning %s (%s)\n", job.name.c_str(), args.job.c_str());

        planner::FieldStageResult result;
        std::optional<planner::LayerStageResult> layers;
        std::optional<daemon::RobotPlan> robot_plan;
        {
            ConsoleProgress progress;
            planner::StepControl control{progress.sink(), nullptr};
            result = planner::run_field_stage(job, control);
            if (args.stage == "layers")
                layers = planner::run_layer_stage(job, result, args.threads, control);
            progress.update("write", 0.0);
            planner::write_field_vtk(args.out + "/field.vtk", result.model.mesh,
                                     {&*result.model.stress, &result.field.sigma_e,
                                      &result.field.v_e, &result.v_defined});
            nlohmann::json report = planner::field_stage_report(job, result);
            if (layers) {
                write_layer_outputs(args.out, job, *layers);
                planner::add_layer_stage_report(report, *layers);
                progress.update("robot", 0.0);
                robot_plan = daemon::plan_robot(job, layers->layers, robot, args.out + "/rapid");
                daemon::add_robot_report(report, *robot_plan);
            }
            report["timings_s"]["total"] = clock.elapsed();
            planner::write_json_file(args.out + "/report.json", report);
        }
        print_summary(result, args.out);
        if (layers) print_layer_summary(*layers, args.out);
        if (robot_plan) print_robot_summary(*robot_plan, args.out);
        return 0;
    } catch (const std::exception& e) {
        // ConfigError, InputError, FeaError and the rest all carry a complete one-line message.
        std::cerr << "fibrecell plan: " << e.what() << "\n";
    }
    return 1;
}

}  // namespace

void add_plan_command(CLI::App& app, int& exit_code) {
    auto args = std::make_shared<PlanArgs>();
    auto* cmd = app.add_subcommand("plan", "plan a job offline and write the plan directory");
    cmd->add_option("job", args->job, "job file (YAML)")->required()->check(CLI::ExistingFile);
    cmd->add_option("--out", args->out, "plan directory to write")->required();
    cmd->add_option("--stage", args->stage,
                    "last stage to run: field (3D vector field) or layers (toolpaths; default)")
        ->check(CLI::IsMember({"field", "layers"}));
    cmd->add_option("--threads", args->threads,
                    "worker threads for the layers (default: all cores)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--cell", args->cell,
                    "cell YAML for the robot program (default: the simulated cell)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--strategy", args->strategy, "override the job's fibre strategy")
        ->check(CLI::IsMember({"field", "contour-zigzag"}));
    cmd->callback([args, &exit_code] { exit_code = run_plan(*args); });
}

}  // namespace fibrecell::tools
