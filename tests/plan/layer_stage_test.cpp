// The layer stage end to end on a bar in uniaxial tension: the layer stack, straight fibres along
// the load, PLA layers, and the plan directory written by `fibrecell plan`.

#include "planner/plan/layer_stage.hpp"
#include "drivers/abb/rapid/reader.hpp"
#include "planner/io/vtk_writer.hpp"
#include "planner/job/job_spec.hpp"
#include "planner/mesh/structured_mesh.hpp"
#include "planner/plan/field_stage.hpp"
#include "planner/plan/toolpaths_json.hpp"
#include "tests/support/plan_inputs.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/project_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>

using namespace fibrecell::planner;
namespace fs = std::filesystem;

namespace {

class LayerStageTest : public ::testing::Test {
  protected:
    void SetUp() override {
        // 100 x 20 x 1.6 mm bar pulled along x: two PLA layers, a CCF layer on each.
        const TetMesh mesh = structured_tet_mesh({.size = {100, 20, 1.6}, .cells = {50, 10, 2}});
        std::vector<StressTensor> stress(mesh.tet_count(), StressTensor::Zero());
        for (auto& s : stress) s(0, 0) = 30.0;
        fibrecell::test::write_vtk_file(dir_ / "bar.vtk", mesh, {.stress = &stress});
        std::ofstream(dir_ / "bar.job.yaml") << "name: bar\nmodel:\n  mesh: bar.vtk\n"
                                                "placement:\n  position_mm: [50, 10]\n";
    }

    fibrecell::test::TempDir dir_{"layer-stage"};
};

}  // namespace

TEST_F(LayerStageTest, BarGetsAlternatingLayersAndStraightFibresAlongTheLoad) {
    const JobSpec job = load_job_file((dir_ / "bar.job.yaml").string());
    const FieldStageResult field = fibrecell::test::field_stage_of(job);
    const LayerStageResult r = run_layer_stage(job, field);
    ASSERT_EQ(r.layers.size(), 4u);
    const Head expected[] = {Head::pla, Head::ccf, Head::pla, Head::ccf};
    const double z[] = {0.8, 0.85, 1.65, 1.7};
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(r.layers[i].head, expected[i]);
        EXPECT_NEAR(r.layers[i].z, z[i], 1e-9);
        EXPECT_FALSE(r.layers[i].paths.empty()) << "layer " << i;
    }
    // Straight runs along x from end to end, W/2 short of the bar's ends (the ribbon stays on the
    // part); the connection (Section 4.4, Step 4) joins runs whose ends are less than 2W apart
    // across the bar's ends, so a path is a serpentine of runs.
    for (const ToolpathLayer& layer : r.layers) {
        if (layer.head != Head::ccf) continue;
        std::set<long> runs;  // run heights [um]
        for (const Toolpath& p : layer.paths) {
            EXPECT_EQ(p.role, PathRole::fibre);
            for (std::size_t i = 0; i + 1 < p.points.size(); ++i) {
                const Eigen::Vector2d a = p.points[i], b = p.points[i + 1];
                EXPECT_TRUE(a.x() >= 0.5 - 1e-4 && a.x() <= 99.5 + 1e-4 && a.y() >= 0.5 - 1e-4 &&
                            a.y() <= 19.5 + 1e-4);
                if (std::abs(a.y() - b.y()) < 1e-4) {
                    runs.insert(std::lround(a.y() * 1000));
                    continue;
                }
                // W/2 in from the bar's ends (and a few um for the offset's arcs).
                const bool at_an_end =
                    std::abs(a.x() - b.x()) < 1e-4 &&
                    ((a.x() >= 0.5 && a.x() < 0.51) || (a.x() <= 99.5 && a.x() > 99.49));
                EXPECT_TRUE(at_an_end) << a.transpose() << " -> " << b.transpose();
                EXPECT_LT((b - a).norm(), 2.0);  // 2W
            }
        }
        ASSERT_GE(runs.size(), 15u);
        for (auto it = std::next(runs.begin()); it != runs.end(); ++it) {
            EXPECT_GE(*it - *std::prev(it), 1000 - 1);  // [um], spacing in [W, 1.25W]
            EXPECT_LE(*it - *std::prev(it), 1250);
        }
    }
    // The PLA infill turns 45 degrees per PLA layer from 0 at the first: its longest segment
    // (a zigzag line across the bar, not a link) lies along x, then along the diagonal.
    int pla_seen = 0;
    for (const ToolpathLayer& layer : r.layers) {
        if (layer.head != Head::pla) continue;
        Eigen::Vector2d longest = Eigen::Vector2d::Zero();
        for (const Toolpath& p : layer.paths)
            if (p.role == PathRole::infill)
                for (std::size_t i = 0; i + 1 < p.points.size(); ++i)
                    if ((p.points[i + 1] - p.points[i]).norm() > longest.norm())
                        longest = p.points[i + 1] - p.points[i];
        ASSERT_GT(longest.norm(), 0) << "PLA layer " << pla_seen + 1 << " has no infill";
        const double deg = std::fmod(std::atan2(longest.y(), longest.x()) * 180 / M_PI + 180, 180);
        EXPECT_NEAR(std::min(deg, 180 - deg), pla_seen == 0 ? 0 : 45, 0.5)
            << "PLA layer " << pla_seen + 1;
        ++pla_seen;
    }
    EXPECT_EQ(r.stats.pla_layers, 2);
    EXPECT_EQ(r.stats.ccf_layers, 2);
    EXPECT_GE(r.stats.fibre_min_length_mm, 98.98);  // at least one full run, W/2 in from the ends
    EXPECT_GT(r.stats.fibre_joins, 20);
    // Straight along the load but for the short joins across it at the bar's ends.
    EXPECT_GT(r.stats.quality.alignment(), 0.98);
}

TEST_F(LayerStageTest, CommandLineWritesThePlanDirectory) {
    const fs::path out = dir_ / "plan";
    const std::string cmd = fibrecell::test::binary_path("tools/fibrecell plan ") +
                            (dir_ / "bar.job.yaml").string() + " --out " + out.string() +
                            " > /dev/null 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    const ToolpathsFile toolpaths = read_toolpaths_json((out / "toolpaths.json").string());
    EXPECT_EQ(toolpaths.strategy, "field");
    EXPECT_EQ(toolpaths.layers.size(), 4u);
    EXPECT_TRUE(fs::exists(out / "preview" / "index.html"));
    EXPECT_TRUE(fs::exists(out / "preview" / "layer_0003.svg"));
    std::ifstream in(out / "report.json");
    const auto report = nlohmann::json::parse(in);
    EXPECT_EQ(report["layers"]["pla"], 2);
    EXPECT_EQ(report["layers"]["ccf"], 2);
    EXPECT_GT(report["fibre"]["length_m"].get<double>(), 1.0);
    // What the cutter rule left out, counted and measured: none of it, or some of both.
    EXPECT_EQ(report["fibre"]["dropped_short"].get<int>() > 0,
              report["fibre"]["dropped_short_m"].get<double>() > 0);
    // Coverage per CCF layer and over both (fibre_coverage_test.cpp checks the figures).
    const auto& coverage = report["fibre"]["coverage"];
    ASSERT_EQ(coverage["layers"].size(), 2u);
    double fibre_m = 0;
    for (const auto& layer : coverage["layers"]) {
        EXPECT_GT(layer["coverage"].get<double>(), 0.1);
        EXPECT_LE(layer["covered"].get<double>(), 1.0);
        EXPECT_GT(layer["paths"].get<int>(), 0);
        fibre_m += layer["fibre_m"].get<double>();
    }
    EXPECT_NEAR(fibre_m, report["fibre"]["length_m"].get<double>(), 1e-9);
    EXPECT_NEAR(coverage["fibre_m"].get<double>(), fibre_m, 1e-9);
    for (const char* key : {"vector_field", "scalar_field", "extraction", "connection"})
        EXPECT_TRUE(report["timings_s"]["per_layer_mean"][key].is_number()) << key;
    // The robot's side: RAPID chunks the project's reader accepts, counted in the report.
    const int modules = report["robot"]["modules"].get<int>();
    ASSERT_GE(modules, 1);
    EXPECT_GT(report["robot"]["moves"].get<int>(), 10);
    EXPECT_GT(report["robot"]["duration_s"].get<double>(), 0.0);
    EXPECT_TRUE(report["timings_s"]["rapid"].is_number());
    namespace rapid = fibrecell::drivers::abb::rapid;
    rapid::ValidateOptions options;
    options.known_signals = {"goFcEvent", "goFcBarrier",   "giFcRelease",   "diFcPause",
                             "diFcAbort", "diFcHeartbeat", "doFcHeartbeat", "doFcRunning"};
    options.external_routines = {"FcMain:FcBarrier"};
    for (int i = 1; i <= modules; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "FcChunk%04d.mod", i);
        const auto r = rapid::check_module_file((out / "rapid" / name).string(), options);
        EXPECT_TRUE(r.ok()) << name << ": "
                            << (r.diagnostics.empty() ? "" : format(r.diagnostics.front()));
    }
}

TEST_F(LayerStageTest, BaselineStrategyProducesRingsAndZigzag) {
    JobSpec job = load_job_file((dir_ / "bar.job.yaml").string());
    job.planner.strategy = Strategy::contour_zigzag;
    const LayerStageResult r = run_layer_stage(job, fibrecell::test::field_stage_of(job));
    bool rings = false, fill = false;
    for (const auto& layer : r.layers)
        for (const auto& p : layer.paths) {
            rings |= p.role == PathRole::fibre_boundary;
            fill |= p.role == PathRole::fibre;
        }
    EXPECT_TRUE(rings && fill);
    // Zigzag at 0 degrees, then 45 (|cos| 1 and 0.71), rings mostly along the load: the same
    // metric tells the strategies apart.
    EXPECT_LT(r.stats.quality.alignment(), 0.95);
    EXPECT_GT(r.stats.quality.alignment(), 0.75);
}
