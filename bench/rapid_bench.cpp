// RAPID generation for a whole plan: toolpaths -> print program (merging, events, clearance
// checks) -> chunk modules (IK per target, text) -> files, for the bundled Loop example by
// default (planned here first, not timed), or for a toolpaths.json given on the command line.
// Target: <= 1 s for the Loop (issue 4). Release build:
//   build/release/bench/rapid_bench [toolpaths.json]
#include "config/durable_file.hpp"
#include "daemon/print/robot_plan.hpp"
#include "drivers/abb/cell/robot_config.hpp"
#include "drivers/abb/program/print_program.hpp"
#include "drivers/abb/rapid/rapid_writer.hpp"
#include "planner/io/read_model.hpp"
#include "planner/job/job_spec.hpp"
#include "planner/plan/field_stage.hpp"
#include "planner/plan/layer_stage.hpp"
#include "planner/plan/toolpaths_json.hpp"
#include "planner/stopwatch.hpp"
#include "tests/support/project_paths.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

using namespace fibrecell;
using namespace fibrecell::drivers::abb;
namespace fs = std::filesystem;

namespace {

struct Times {
    double program = 0, rapid = 0, files = 0;
    double total() const { return program + rapid + files; }
};

}  // namespace

int main(int argc, char** argv) {
    spdlog::set_level(spdlog::level::warn);
    std::vector<planner::ToolpathLayer> layers;
    planner::ProcessSpec process;
    double cutter_mm = 42;
    std::string source;
    if (argc > 1) {
        source = argv[1];
        layers = planner::read_toolpaths_json(source).layers;
    } else {
        source = "examples/loop/loop.job.yaml (planned now, not timed)";
        const planner::JobSpec job =
            planner::load_job_file(fibrecell::test::source_path("examples/loop/loop.job.yaml"));
        const planner::FieldStageResult field = planner::run_field_stage(
            job, planner::read_volume_model(job.model.mesh_path, job.model.stress_path));
        layers = planner::run_layer_stage(job, field, {.cutter_distance_mm = cutter_mm}).layers;
        process = job.process;
    }
    std::size_t paths = 0, points = 0;
    for (const auto& l : layers) {
        paths += l.paths.size();
        for (const auto& p : l.paths) points += p.points.size();
    }

    const std::vector<RobotLayer> robot_layers = daemon::print::robot_layers(layers);  // not timed
    const RobotCellConfig cell;  // the simulated cell's defaults
    const ProgramOptions options{.pla_speed_mm_s = process.pla.speed_mm_s,
                                 .ccf_speed_mm_s = process.ccf.speed_mm_s,
                                 .pla_travel_speed_mm_s = process.pla.travel_speed_mm_s,
                                 .ccf_travel_speed_mm_s = process.ccf.travel_speed_mm_s,
                                 .cutter_distance_mm = cutter_mm};
    const fs::path dir = fs::temp_directory_path() / "fibrecell-rapid-bench" / "rapid";
    constexpr int runs = 5;
    std::vector<Times> times;
    PrintProgram program;
    RapidOutput rapid;
    for (int r = 0; r < runs; ++r) {
        Times t;
        planner::Stopwatch clock;
        program = build_print_program(robot_layers, cell, options);
        t.program = clock.lap();
        rapid = write_rapid_chunks(program, cell, {.job_name = "bench"});
        t.rapid = clock.lap();
        fs::remove_all(dir);
        fibrecell::config::DurableFiles files(dir);
        for (const RapidModule& m : rapid.modules) files.write(m.file_name, m.text);
        files.commit();
        t.files = clock.lap();
        times.push_back(t);
    }
    fs::remove_all(dir.parent_path());
    std::sort(times.begin(), times.end(),
              [](const Times& a, const Times& b) { return a.total() < b.total(); });
    const Times& median = times[runs / 2];
    const Times& best = times.front();

    const ProgramStats& s = program.stats;
    std::printf("RAPID generation, Release, one thread, median of %d runs\n", runs);
    std::printf("input    %s\n", source.c_str());
    std::printf("         %zu layers, %zu paths, %zu points\n", layers.size(), paths, points);
    std::printf(
        "program  %zu moves (%zu print), %zu points merged away, %zu events (%zu barriers),"
        " %zu head switches, %.1f m printed, estimated %.0f s (%.1f h)\n",
        s.moves, s.print_moves, s.points_merged, s.events, s.barriers, s.head_switches,
        s.print_length_mm / 1000, s.duration_s, s.duration_s / 3600);
    std::printf("rapid    %zu chunks, %zu lines, %.1f MB, %zu IK solves\n", rapid.stats.modules,
                rapid.stats.lines, static_cast<double>(rapid.stats.bytes) / 1e6, rapid.stats.moves);
    std::printf(
        "time     program %.3f s + chunks (IK + text) %.3f s + files (fsynced) %.3f s = %.3f s "
        "(best %.3f s; target <= 1 s)\n",
        median.program, median.rapid, median.files, median.total(), best.total());
    std::printf("         %.2f M targets/s through IK and text\n",
                static_cast<double>(rapid.stats.moves) / median.rapid / 1e6);
    return 0;
}
