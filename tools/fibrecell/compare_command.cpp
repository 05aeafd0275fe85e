#include "tools/fibrecell/compare_command.hpp"

#include "daemon/cell/cell_config.hpp"
#include "daemon/jobs/plan_job.hpp"
#include "daemon/jobs/thread_pool.hpp"
#include "tools/fibrecell/console_progress.hpp"
#include "tools/fibrecell/planning_options.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

namespace fibrecell::tools {
namespace {

namespace jobs = daemon::jobs;

struct CompareArgs {
    std::string job;
    std::string out;
    std::string cell;  // cell YAML; empty: the simulated cell's defaults
    int threads = 0;
};

jobs::PlanJobResult plan_one(jobs::PlanRequest request, const char* what) {
    std::fprintf(stderr, "planning %s (%s)\n", what, request.job_file.c_str());
    ConsoleProgress progress;
    return jobs::plan_job(request, {progress.sink(), nullptr});
}

const planner::MechanicsResult& mechanics_of(const jobs::PlanJobResult& plan) {
    if (!plan.mechanics)
        throw std::invalid_argument(
            "the job has no load case to compare the strategies under: give model.load_case, "
            "or analysis.load_case for a model with a stress file (docs/mechanics.md)");
    return *plan.mechanics;
}

nlohmann::json column(double fibre_m, const planner::PartResponse& r, double bare_stiffness) {
    return {
        {"fibre_m", fibre_m},
        {"stiffness_n_per_mm", r.stiffness_n_per_mm},
        {"vs_no_fibre", r.stiffness_n_per_mm / bare_stiffness},
        {"matrix_von_mises_mpa", {{"peak", r.von_mises_peak_mpa}, {"p99", r.von_mises_p99_mpa}}},
        {"fibre_stress_peak_mpa", r.fibre_stress_peak_mpa}};
}

void print_table(const nlohmann::json& c) {
    const auto& none = c["no_fibre"];
    const auto& zig = c["contour_zigzag"];
    const auto& field = c["field"];
    std::printf("\n%-26s %12s %15s %12s\n", "", "no fibre", "contour-zigzag", "field");
    std::printf("%-26s %12s %15.2f %12.2f\n", "fibre [m]", "-", zig["fibre_m"].get<double>(),
                field["fibre_m"].get<double>());
    auto row = [&](const char* name, const char* key) {
        std::printf("%-26s %12.1f %15.1f %12.1f\n", name, none[key].get<double>(),
                    zig[key].get<double>(), field[key].get<double>());
    };
    row("stiffness [N/mm]", "stiffness_n_per_mm");
    std::printf("%-26s %12.2f %15.2f %12.2f\n", "  vs no fibre", 1.0,
                zig["vs_no_fibre"].get<double>(), field["vs_no_fibre"].get<double>());
    std::printf("%-26s %12s %15.2f %12.2f\n", "  vs contour-zigzag", "", 1.0,
                c["field_vs_contour_zigzag"].get<double>());
    std::printf("%-26s %12.1f %15.1f %12.1f\n", "PLA von Mises peak [MPa]",
                none["matrix_von_mises_mpa"]["peak"].get<double>(),
                zig["matrix_von_mises_mpa"]["peak"].get<double>(),
                field["matrix_von_mises_mpa"]["peak"].get<double>());
    std::printf("%-26s %12.1f %15.1f %12.1f\n", "PLA von Mises p99 [MPa]",
                none["matrix_von_mises_mpa"]["p99"].get<double>(),
                zig["matrix_von_mises_mpa"]["p99"].get<double>(),
                field["matrix_von_mises_mpa"]["p99"].get<double>());
    std::printf("%-26s %12s %15.0f %12.0f\n", "fibre stress peak [MPa]", "-",
                zig["fibre_stress_peak_mpa"].get<double>(),
                field["fibre_stress_peak_mpa"].get<double>());
}

int run_compare(const CompareArgs& args) {
    try {
        const std::filesystem::path out(args.out);
        jobs::ThreadPool pool({.threads = args.threads});
        jobs::PlanRequest request{.job_file = args.job, .executor = &pool};
        if (!args.cell.empty()) request.cell = daemon::load_cell_config(args.cell);

        request.out_dir = out / "field";
        request.strategy = planner::Strategy::field;
        const jobs::PlanJobResult field = plan_one(request, "the field strategy");
        const planner::MechanicsResult& fm = mechanics_of(field);
        const auto& fs = field.layers->stats;
        if (fs.ccf_layers == 0 || fs.fibre_length_mm <= 0)
            throw std::invalid_argument("the field strategy laid no fibre: nothing to compare");

        // The paper's comparison: the same fibre, in a different place.
        request.out_dir = out / "contour-zigzag";
        request.strategy = planner::Strategy::contour_zigzag;
        request.fibre_budget = planner::FibreBudget{planner::FibreBudget::Kind::metres_per_layer,
                                                    fs.fibre_length_mm / 1000.0 / fs.ccf_layers};
        const jobs::PlanJobResult zigzag = plan_one(request, "contour-zigzag at the same fibre");
        const planner::MechanicsResult& zm = mechanics_of(zigzag);

        const double bare = fm.prediction.bare.stiffness_n_per_mm;
        nlohmann::json c = {
            {"format", "fibrecell.compare/1"},
            {"job", field.job.name},
            {"no_fibre", column(0, fm.prediction.bare, bare)},
            {"contour_zigzag", column(zm.fibre_placed_mm / 1000.0, zm.prediction.reinforced, bare)},
            {"field", column(fm.fibre_placed_mm / 1000.0, fm.prediction.reinforced, bare)},
            {"field_vs_contour_zigzag", fm.prediction.reinforced.stiffness_n_per_mm /
                                            zm.prediction.reinforced.stiffness_n_per_mm},
            {"fibre_budget_m_per_layer", request.fibre_budget->metres_per_layer}};
        print_table(c);
        std::ofstream(out / "compare.json") << c.dump(2) << "\n";
        std::printf("\nwrote      %s/compare.json, plans in %s/field and %s/contour-zigzag\n",
                    args.out.c_str(), args.out.c_str(), args.out.c_str());
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "fibrecell compare: " << e.what() << "\n";
    }
    return 1;
}

}  // namespace

void add_compare_command(CLI::App& app, int& exit_code) {
    auto args = std::make_shared<CompareArgs>();
    auto* cmd = app.add_subcommand(
        "compare", "plan a job with both strategies at the same fibre and predict their stiffness");
    cmd->add_option("job", args->job, "job file (YAML)")->required()->check(CLI::ExistingFile);
    cmd->add_option("--out", args->out, "folder for both plans and compare.json")->required();
    add_planning_options(cmd, args->threads, args->cell);
    cmd->callback([args, &exit_code] { exit_code = run_compare(*args); });
}

}  // namespace fibrecell::tools
