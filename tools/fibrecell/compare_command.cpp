#include "tools/fibrecell/compare_command.hpp"

#include "daemon/cell/cell_config.hpp"
#include "daemon/jobs/plan_job.hpp"
#include "daemon/jobs/thread_pool.hpp"
#include "planner/plan/fibre_ceiling.hpp"
#include "planner/plan/mechanics_stage.hpp"
#include "tools/fibrecell/console_progress.hpp"
#include "tools/fibrecell/planning_options.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

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

// The predicted response of a part, as compare.json's columns have it.
nlohmann::json response_column(const planner::PartResponse& r, double bare_stiffness) {
    return {{"stiffness_n_per_mm", r.stiffness_n_per_mm},
            {"vs_no_fibre", r.stiffness_n_per_mm / bare_stiffness},
            {"matrix_von_mises_mpa", {{"peak", r.von_mises_peak_mpa}, {"p99", r.von_mises_p99_mpa}}},
            {"fibre_stress_peak_mpa", r.fibre_stress_peak_mpa}};
}

// A plan's column: its response and the fibre it placed, how much of the fibre region it covers.
nlohmann::json plan_column(const jobs::PlanJobResult& plan, double bare_stiffness) {
    const planner::MechanicsResult& m = mechanics_of(plan);
    nlohmann::json c = response_column(m.prediction.reinforced, bare_stiffness);
    const auto& stats = plan.layers->stats;
    c["fibre_m"] = m.fibre_placed_mm / 1000.0;
    c["coverage"] = stats.coverage.coverage();
    c["covered"] = stats.coverage.covered_fraction();
    c["paths"] = stats.fibre_paths;
    return c;
}

// A table of columns (each a compare.json object), rows of figures, "-" where a column has none.
void print_table(const char* heading, const std::vector<std::pair<std::string, const nlohmann::json*>>& cols) {
    std::printf("\n%s\n%-26s", heading, "");
    for (const auto& [title, c] : cols) std::printf(" %15s", title.c_str());
    std::printf("\n");
    const auto row = [&](const char* name, auto value, int digits) {
        std::printf("%-26s", name);
        for (const auto& [title, c] : cols) {
            const std::optional<double> v = value(*c);
            if (v)
                std::printf(" %15.*f", digits, *v);
            else
                std::printf(" %15s", "-");
        }
        std::printf("\n");
    };
    const auto key = [](const char* k) {
        return [k](const nlohmann::json& c) -> std::optional<double> {
            if (!c.contains(k)) return std::nullopt;
            return c[k].get<double>();
        };
    };
    const auto stress = [](const char* which) {
        return [which](const nlohmann::json& c) -> std::optional<double> {
            if (!c.contains("matrix_von_mises_mpa")) return std::nullopt;
            return c["matrix_von_mises_mpa"][which].get<double>();
        };
    };
    row("fibre [m]", key("fibre_m"), 2);
    row("coverage", key("coverage"), 3);
    row("paths", key("paths"), 0);
    row("stiffness [N/mm]", key("stiffness_n_per_mm"), 1);
    row("  vs no fibre", key("vs_no_fibre"), 2);
    row("  of the ceiling's gain", key("of_ceiling_gain"), 2);
    row("PLA von Mises peak [MPa]", stress("peak"), 1);
    row("PLA von Mises p99 [MPa]", stress("p99"), 1);
    row("fibre stress peak [MPa]", key("fibre_stress_peak_mpa"), 0);
}

int run_compare(const CompareArgs& args) {
    try {
        const std::filesystem::path out(args.out);
        jobs::ThreadPool pool({.threads = args.threads});
        jobs::PlanRequest request{.job_file = args.job, .executor = &pool};
        if (!args.cell.empty()) request.cell = daemon::load_cell_config(args.cell);
        const auto plan_as = [&](planner::Strategy strategy, const std::string& dir,
                                 std::optional<planner::FibreBudget> budget, const char* what) {
            request.out_dir = out / dir;
            request.strategy = strategy;
            request.fibre_budget = budget;
            jobs::PlanJobResult plan = plan_one(request, what);
            mechanics_of(plan);  // a job without a load case stops here
            return plan;
        };

        const jobs::PlanJobResult field =
            plan_as(planner::Strategy::field, "field", std::nullopt, "the field strategy");
        const auto& fs = field.layers->stats;
        if (fs.ccf_layers == 0 || fs.fibre_length_mm <= 0)
            throw std::invalid_argument("the field strategy laid no fibre: nothing to compare");
        // The paper's comparison: the same fibre (the field's, per CCF layer), in other places.
        const planner::FibreBudget same{planner::FibreBudget::Kind::metres_per_layer,
                                        fs.fibre_length_mm / 1000.0 / fs.ccf_layers};
        const jobs::PlanJobResult zigzag = plan_as(planner::Strategy::contour_zigzag, "contour-zigzag",
                                                   same, "contour-zigzag at the same fibre");
        const jobs::PlanJobResult dense = plan_as(planner::Strategy::field_dense, "field-dense", same,
                                                  "field-dense at the same fibre");
        // And each as much as it lays at its own defaults.
        const jobs::PlanJobResult zigzag_own = plan_as(
            planner::Strategy::contour_zigzag, "contour-zigzag-defaults", std::nullopt,
            "contour-zigzag at its defaults");
        const jobs::PlanJobResult dense_own = plan_as(
            planner::Strategy::field_dense, "field-dense-defaults", std::nullopt,
            "field-dense at its defaults");

        // The ceiling: the field's sections laid full, all along the principal direction.
        std::fprintf(stderr, "predicting the ceiling (every section full, along the stress)\n");
        const planner::MechanicsResult ceiling = planner::run_mechanics_stage(
            field.job, field.field, planner::ideal_fibre_layers(field.job, field.field, *field.layers));

        const planner::PartResponse& bare_part = mechanics_of(field).prediction.bare;
        const double bare = bare_part.stiffness_n_per_mm;
        const auto of = [&](const jobs::PlanJobResult* plan) { return plan_column(*plan, bare); };
        nlohmann::json no_fibre = response_column(bare_part, bare);
        no_fibre["fibre_m"] = 0.0;
        no_fibre.erase("fibre_stress_peak_mpa");
        nlohmann::json c = {
            {"format", "fibrecell.compare/1"},
            {"job", field.job.name},
            {"no_fibre", no_fibre},
            {"contour_zigzag", of(&zigzag)},
            {"field", of(&field)},
            {"field_dense", of(&dense)},
            {"fibre_budget_m_per_layer", same.metres_per_layer},
            {"own_defaults",
             {{"contour_zigzag", of(&zigzag_own)},
              {"field", of(&field)},
              {"field_dense", of(&dense_own)}}}};
        c["ceiling"] = response_column(ceiling.prediction.reinforced, bare);
        c["ceiling"]["fibre_m"] = ceiling.fibre_placed_mm / 1000.0;
        c["ceiling"]["of_ceiling_gain"] = 1.0;
        // How much of the possible gain each plan takes.
        const double possible = ceiling.prediction.reinforced.stiffness_n_per_mm - bare;
        for (auto* column : {&c["contour_zigzag"], &c["field"], &c["field_dense"],
                             &c["own_defaults"]["contour_zigzag"], &c["own_defaults"]["field"],
                             &c["own_defaults"]["field_dense"]})
            (*column)["of_ceiling_gain"] =
                possible > 0 ? ((*column)["stiffness_n_per_mm"].get<double>() - bare) / possible : 0.0;
        c["field_vs_contour_zigzag"] =
            c["field"]["stiffness_n_per_mm"].get<double>() / c["contour_zigzag"]["stiffness_n_per_mm"].get<double>();
        const auto& own = c["own_defaults"];
        print_table("At the same fibre (the field strategy's, per CCF layer):",
                    {{"no fibre", &c["no_fibre"]}, {"contour-zigzag", &c["contour_zigzag"]},
                     {"field", &c["field"]}, {"field-dense", &c["field_dense"]}});
        print_table("Each at its own defaults, and the ceiling (every section full, along the stress):",
                    {{"no fibre", &c["no_fibre"]}, {"contour-zigzag", &own["contour_zigzag"]},
                     {"field", &own["field"]}, {"field-dense", &own["field_dense"]},
                     {"ceiling", &c["ceiling"]}});
        std::printf("\nfield / contour-zigzag at the same fibre: %.3f\n",
                    c["field_vs_contour_zigzag"].get<double>());
        std::ofstream(out / "compare.json") << c.dump(2) << "\n";
        std::printf("\nwrote      %s/compare.json, plans in %s/{field,contour-zigzag,field-dense} "
                    "(same fibre) and %s/{contour-zigzag,field-dense}-defaults\n",
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
        "compare", "plan a job with each strategy, at the same fibre and at its defaults, and predict the stiffness");
    cmd->add_option("job", args->job, "job file (YAML)")->required()->check(CLI::ExistingFile);
    cmd->add_option("--out", args->out, "folder for both plans and compare.json")->required();
    add_planning_options(cmd, args->threads, args->cell);
    cmd->callback([args, &exit_code] { exit_code = run_compare(*args); });
}

}  // namespace fibrecell::tools
