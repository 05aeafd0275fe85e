// Benchmark of the predicted stiffness (planner/plan/mechanics_stage, docs/mechanics.md): the
// Loop example and a Shell-sized Loop-like plate (about 112k tets) planned like `fibrecell plan`,
// then the fibre located in the tets and the load case solved bare and reinforced.
// Release build:  build/release-by-hand/bench/mechanics_bench

#include "bench_parts.hpp"
#include "config/durable_file.hpp"
#include "daemon/jobs/plan_job.hpp"
#include "daemon/jobs/thread_pool.hpp"
#include "planner/fea/linear_elastic.hpp"
#include "planner/io/vtk_writer.hpp"
#include "planner/stopwatch.hpp"
#include "tests/support/project_paths.hpp"

#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>

using namespace fibrecell::planner;
namespace fs = std::filesystem;
namespace jobs = fibrecell::daemon::jobs;

namespace {

void plan_and_print(const char* name, const fs::path& job_file, jobs::ThreadPool& pool,
                    const fs::path& out) {
    const jobs::PlanJobResult r =
        jobs::plan_job({.job_file = job_file, .out_dir = out, .executor = &pool});
    const MechanicsResult& m = *r.mechanics;
    const StiffnessPrediction& p = m.prediction;
    const FeaTimings& t = p.reinforced.fea;
    std::printf(
        "%-6s %7zu %6.3f | %6.3f %6.3f %6.3f (%5.3f %5.3f %5.3f %5.3f) %6.3f | %6.1f m "
        "%8.0f %8.0f %5.2fx\n",
        name, r.field.model.mesh.tet_count(), r.field.timings.fea, m.locate_s, p.bare.fea.total_s,
        p.reinforced.fea.total_s, t.assembly_s, t.factorisation_s, t.solve_s, t.stress_s, m.seconds,
        m.fibre_placed_mm / 1000.0, p.bare.stiffness_n_per_mm, p.reinforced.stiffness_n_per_mm,
        p.gain());
}

// The plate clamped at x = 0 and pulled with 2 kN at x = 140, as a job with its own load case.
fs::path write_plate_job(const fs::path& dir, int tets) {
    const TetMesh mesh = fibrecell::bench::loop_like_plate(tets);
    fibrecell::config::write_file_durably(dir / "plate.vtk", field_vtk_text(mesh, {}));
    const fs::path job = dir / "plate.job.yaml";
    fibrecell::config::write_file_durably(
        job,
        "name: plate\nmodel:\n  mesh: plate.vtk\n  load_case:\n    supports: [x0]\n"
        "    loads: [{region: x140, force_n: [2000, 0, 0]}]\n"
        "regions:\n  x0: {box: {min: [-1, -1, -1], max: [0.001, 101, 11]}}\n"
        "  x140: {box: {min: [139.999, -1, -1], max: [141, 101, 11]}}\n");
    return job;
}

}  // namespace

int main() {
    spdlog::set_level(spdlog::level::warn);  // the table is the output
    const fs::path tmp = fs::temp_directory_path() / "fibrecell-mechanics-bench";
    fs::create_directories(tmp);
    std::printf("Predicted stiffness, Release, 2 threads for the layers\n\n");
    std::printf(
        "bare: the field stage's FEA reused (0) or solved again; fibre: the reinforced "
        "solve (assembly, factorisation, solve, stress)\n\n");
    std::printf("%-6s %7s %6s | %6s %6s %6s %31s %6s | %8s %8s %8s %6s\n", "part", "tets", "fea s",
                "locate", "bare", "fibre", "(asm   fact  solve stress)", "total", "fibre", "k bare",
                "k fibre", "gain");
    jobs::ThreadPool pool({.threads = 2});
    plan_and_print("Loop", fibrecell::test::source_path("examples/loop/loop.job.yaml"), pool, tmp / "loop");
    plan_and_print("Shell", write_plate_job(tmp, 112080), pool, tmp / "plate");
    fs::remove_all(tmp);
    return 0;
}
