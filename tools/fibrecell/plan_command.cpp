#include "tools/fibrecell/plan_command.hpp"

#include "planner/io/vtk_writer.hpp"
#include "planner/job/job_spec.hpp"
#include "planner/plan/field_stage.hpp"
#include "planner/plan/report.hpp"
#include "planner/stopwatch.hpp"
#include "tools/fibrecell/console_progress.hpp"

#include <spdlog/spdlog.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

namespace fibrecell::tools {
namespace {

struct PlanArgs {
    std::string job;
    std::string out;
    std::string stage = "field";
    std::string strategy;
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

int run_plan(const PlanArgs& args) {
    planner::Stopwatch clock;
    try {
        planner::JobSpec job = planner::load_job_file(args.job);
        if (!args.strategy.empty())
            job.planner.strategy = args.strategy == "field" ? planner::Strategy::field
                                                            : planner::Strategy::contour_zigzag;
        std::filesystem::create_directories(args.out);
        std::fprintf(stderr, "planning %s (%s)\n", job.name.c_str(), args.job.c_str());

        planner::FieldStageResult result;
        {
            ConsoleProgress progress;
            planner::StepControl control{progress.sink(), nullptr};
            result = planner::run_field_stage(job, control);
            progress.update("write", 0.0);
            planner::write_field_vtk(args.out + "/field.vtk", result.model.mesh,
                                     {&*result.model.stress, &result.field.sigma_e,
                                      &result.field.v_e, &result.v_defined});
            result.timings.total = clock.elapsed();
            planner::write_json_file(args.out + "/report.json",
                                     planner::field_stage_report(job, result));
        }
        print_summary(result, args.out);
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
    cmd->add_option("--stage", args->stage, "last stage to run (this version: field)")
        ->check(CLI::IsMember({"field"}));
    cmd->add_option("--strategy", args->strategy, "override the job's fibre strategy")
        ->check(CLI::IsMember({"field", "contour-zigzag"}));
    cmd->callback([args, &exit_code] { exit_code = run_plan(*args); });
}

}  // namespace fibrecell::tools
