// board-check PLAN_DIR EDGE_LOG: the feed of every planned path against what gt2560-avr's pins
// show (tools/board-check/board_check.hpp); exit 0 when every path is within the tolerance and
// there are as many feeds and cuts as planned, 1 otherwise, 2 on a bad file.
#include "tools/board-check/board_check.hpp"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>

int main(int argc, char** argv) {
    fibrecell::tools::BoardCheckOptions o;
    std::string plan, edges;
    CLI::App app{"Compare a plan with the pin edges of the board that printed it"};
    app.add_option("plan", plan, "the job's plan directory (program.json, print.json)")->required();
    app.add_option("edges", edges, "gt2560-avr's --edge-log")->required();
    app.add_option("--steps-per-mm", o.steps_per_mm, "E steps/mm of the firmware build")
        ->check(CLI::PositiveNumber);
    app.add_flag("--invert-e-dir", o.invert_e_dir, "dir low is forward");
    app.add_option("--tolerance", o.tolerance, "relative, per path")->check(CLI::PositiveNumber);
    CLI11_PARSE(app, argc, argv);
    try {
        const auto r = fibrecell::tools::check_board(plan, edges, o);
        std::printf("%-6s %5s %4s %11s %11s %8s\n", "path", "layer", "#", "planned mm", "fed mm", "error");
        for (const auto& p : r.paths)
            std::printf("%-6s %5d %4d %11.3f %11.3f %7.3f%%\n", p.kind.c_str(), p.layer, p.path,
                        p.planned_mm, p.fed_mm, 100 * p.error());
        std::printf("fibre feeds %d of %d planned, PLA feeds %d of %d, cuts %d of %d; worst %.3f%%\n",
                    r.fibre_runs, r.planned_fibre_paths, r.pla_runs, r.planned_pla_paths, r.cuts,
                    r.planned_cuts, 100 * r.worst_error);
        for (const auto& problem : r.problems) std::printf("problem: %s\n", problem.c_str());
        std::printf("%s\n", r.problems.empty() ? "board-check: the board fed and cut as planned"
                                               : "board-check: the board did not do what was planned");
        return r.problems.empty() ? 0 : 1;
    } catch (const std::exception& e) {
        std::cerr << e.what() << '\n';
        return 2;
    }
}
