#include "tools/fibrecell/plan_command.hpp"

#include "daemon/cell/cell_config.hpp"
#include "daemon/jobs/plan_job.hpp"
#include "daemon/jobs/thread_pool.hpp"
#include "tools/fibrecell/console_progress.hpp"
#include "tools/fibrecell/planning_options.hpp"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

namespace fibrecell::tools {
namespace {

namespace jobs = daemon::jobs;

struct PlanArgs {
    std::string job;
    std::string out;
    std::string stage = "layers";
    std::string strategy;
    std::string cell;   // cell YAML; empty: the simulated cell's defaults
    std::string sweep;  // NAME=V1,V2,...; empty: none
    int threads = 0;
};

void print_summary(const planner::JobSpec& job, const planner::FieldStageResult& r,
                   const std::string& out) {
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
    const auto& dots = r.neighbour_dots;
    std::printf("neighbours %.2f%% of %llu neighbour pairs disagree (v.v* <= eta = %g)%s%s\n",
                dots.pairs ? 100.0 * static_cast<double>(dots.at_most_eta) / dots.pairs : 0.0,
                static_cast<unsigned long long>(dots.pairs), job.planner.eta,
                job.planner.mst_reorientation ? "" : "; MST re-orientation off",
                job.planner.incompatibility_removal ? "" : "; incompatibility removal off");
    std::printf(
        "timings    read %.3f s, fea %.3f s, principal %.3f s, mst %.3f s, removal %.3f s, "
        "total %.3f s\n",
        t.read, t.fea, t.principal, t.mst_reorientation, t.incompatible_removal, t.total);
    std::printf("wrote      %s/field.vtk, %s/report.json\n", out.c_str(), out.c_str());
}

void print_robot_summary(const daemon::print::RobotPlan& plan,
                         const daemon::print::PrintSettings& settings, const std::string& out) {
    const auto& s = plan.program.stats;
    std::printf(
        "robot      %zu moves, %zu events (%zu barriers), %zu head switches, about %.0f min of "
        "printing; %zu RAPID modules (%zu lines) in %.3f s\n",
        s.moves, s.events, s.barriers, s.head_switches, s.duration_s / 60.0,
        plan.rapid.stats.modules, plan.rapid.stats.lines, plan.seconds);
    std::printf(
        "print      PLA %.0f degC at %g mm/s (travel %g), CCF %.0f degC at %g mm/s (travel %g), "
        "cut %g mm before each fibre path's end\n",
        settings.pla.temp_c, settings.pla.speed_mm_s, settings.pla.travel_speed_mm_s,
        settings.ccf.temp_c, settings.ccf.speed_mm_s, settings.ccf.travel_speed_mm_s,
        settings.cutter_distance_mm);
    std::printf("wrote      %s/rapid/, %s/program.json, %s/print.json, %s/manifest.json\n",
                out.c_str(), out.c_str(), out.c_str(), out.c_str());
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
        "as too short: %.2f m); PLA %.2f m\n",
        s.fibre_length_mm / 1000.0, s.fibre_paths, s.fibre_min_spacing_mm, s.fibre_min_length_mm,
        s.dropped_short, s.dropped_short_mm / 1000.0, s.pla_length_mm / 1000.0);
    if (s.ccf_layers > 0) {
        // The layer with the least coverage is where a denser strategy has most to add.
        const auto least = std::min_element(
            s.layer_coverage.begin(), s.layer_coverage.end(),
            [](const auto& a, const auto& b) { return a.second.coverage() < b.second.coverage(); });
        std::printf(
            "coverage   %.3f (fibre length x W over the fibre region, %.0f mm^2), %.3f of the region "
            "under a ribbon; least on layer %d: %.3f; mean path %.1f mm\n",
            s.coverage.coverage(), s.coverage.region_mm2, s.coverage.covered_fraction(),
            least->first + 1, least->second.coverage(),  // counted from 1, as the dashboard does
            s.fibre_paths > 0 ? s.fibre_length_mm / s.fibre_paths : 0.0);
    }
    if (s.budget.layers > 0) {
        std::printf("budget     %.2f m asked: %d of %d CCF layers within 5%% (worst %.1f%%)",
                    s.budget.target_mm / 1000.0, s.budget.layers_met, s.budget.layers,
                    100 * s.budget.worst_error);
        if (s.budget.p_layers > 0)
            std::printf("; density contrast p %.2f to %.2f", s.budget.lowest_p, s.budget.highest_p);
        std::printf("\n");
    }
    std::printf(
        "quality    fibres along the tension: stress-weighted |cos| %.3f; density vs "
        "sigma^p correlation %.3f; turning %.0f deg/m\n",
        s.quality.alignment(), s.quality.density_correlation(), s.quality.turning_deg_per_m());
    for (const auto& [name, b] : s.boundaries) {
        std::printf("boundary   %s: fibre alongside %.1f%% of its %.2f m; ", name.c_str(),
                    100.0 * b.coverage(), b.edge_mm / 1000.0);
        if (b.rings == 0)
            std::printf("no ring of its own");
        else
            std::printf(
                "%d rings (%.2f m) at %.2f mm from the edge (median; 5th percentile %.2f)", b.rings,
                b.ring_mm / 1000.0, b.ring_distance_quantile(0.5), b.ring_distance_quantile(0.05));
        std::printf("; %d short rings joined onto stress paths, %d joins\n", b.rings_joined,
                    b.joins);
    }
    for (const auto& w : layers.warnings) std::printf("warning    %s\n", w.c_str());
    std::printf("wrote      %s/toolpaths.json, %s/preview/index.html\n", out.c_str(), out.c_str());
}

void print_sweep_summary(const planner::ParameterSweep& sweep) {
    const int w = std::max(10, static_cast<int>(sweep.parameter.size()));
    std::printf("sweep      %-*s fibre [m]  paths  |cos|   corr   turning [deg/m]  time [s]\n", w,
                sweep.parameter.c_str());
    for (const auto& p : sweep.points)
        std::printf("           %-*g %9.2f  %5d  %.3f  %6.3f  %15.0f  %8.2f\n", w, p.value,
                    p.fibre_length_mm / 1000.0, p.fibre_paths, p.alignment, p.density_correlation,
                    p.turning_deg_per_m, p.seconds);
}

void print_mechanics_summary(const planner::MechanicsResult& m) {
    const auto& p = m.prediction;
    std::printf(
        "stiffness  %.1f N/mm with the fibre, %.1f N/mm without (%.2fx); %.2f m of fibre in %d "
        "tets (%.0f mm3), predicted in %.2f s\n",
        p.reinforced.stiffness_n_per_mm, p.bare.stiffness_n_per_mm, p.gain(),
        m.fibre_placed_mm / 1000.0, m.reinforced_tets, m.fibre_volume_mm3, m.seconds);
    std::printf(
        "stress     PLA von Mises peak %.1f MPa, p99 %.1f MPa (bare %.1f / %.1f); fibre peak "
        "%.0f MPa\n",
        p.reinforced.von_mises_peak_mpa, p.reinforced.von_mises_p99_mpa, p.bare.von_mises_peak_mpa,
        p.bare.von_mises_p99_mpa, p.reinforced.fibre_stress_peak_mpa);
}

int run_plan(const PlanArgs& args) {
    try {
        jobs::PlanRequest request{.job_file = args.job, .out_dir = args.out};
        if (!args.sweep.empty()) {
            if (args.stage != "layers")
                throw std::invalid_argument("--sweep plans layers: it needs --stage layers");
            request.sweep = planner::parse_sweep(args.sweep);
        }
        request.last_stage =
            args.stage == "layers" ? jobs::PlanStage::layers : jobs::PlanStage::field;
        if (!args.strategy.empty()) request.strategy = planner::strategy_named(args.strategy);
        if (!args.cell.empty()) request.cell = daemon::load_cell_config(args.cell);
        jobs::ThreadPool pool({.threads = args.threads});
        request.executor = &pool;

        std::optional<jobs::PlanJobResult> plan;
        {
            ConsoleProgress progress;
            plan = jobs::plan_job(
                request, {progress.sink(), nullptr}, [&](const planner::JobSpec& job) {
                    std::fprintf(stderr, "planning %s (%s)\n", job.name.c_str(), args.job.c_str());
                });
        }
        print_summary(plan->job, plan->field, args.out);
        if (plan->layers) print_layer_summary(*plan->layers, args.out);
        if (plan->sweep) print_sweep_summary(*plan->sweep);
        if (plan->mechanics) print_mechanics_summary(*plan->mechanics);
        if (plan->robot) print_robot_summary(*plan->robot, plan->settings, args.out);
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
    add_planning_options(cmd, args->threads, args->cell);
    cmd->add_option("--sweep", args->sweep,
                    "plan the layers again at several values of a planner setting, for the "
                    "report and preview (p=0,0.5,1,2; also sigma_cap_percentile, "
                    "crowded_fraction)");
    cmd->add_option("--strategy", args->strategy, "override the job's fibre strategy")
        ->check(CLI::IsMember({"field", "contour-zigzag", "field-dense"}));
    cmd->callback([args, &exit_code] { exit_code = run_plan(*args); });
}

}  // namespace fibrecell::tools
