// plan_job, the one planning path of the service and the offline CLI, on a small bar in uniform
// tension: the plan directory, progress per stage, cancel, the field stage alone, and
// `fibrecell plan` writing the same toolpaths as the library.
#include "daemon/jobs/plan_job.hpp"

#include "daemon/print/manifest.hpp"

#include "job_test_files.hpp"
#include "planner/mesh/structured_mesh.hpp"
#include "planner/plan/toolpaths_json.hpp"
#include "tests/support/project_paths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

using namespace fibrecell;
using namespace fibrecell::daemon::jobs;
using fibrecell::daemon::CellConfig;
using fibrecell::test::read_file;
namespace fs = std::filesystem;

namespace {

class PlanJobTest : public ::testing::Test {
  protected:
    void SetUp() override {
        test::write_tension_bar(dir_ / "bar.vtk");
        std::ofstream(dir_ / "bar.job.yaml") << "name: bar\nmodel:\n  mesh: bar.vtk\n";
    }

    PlanRequest request(const std::string& out) const {
        return {.job_file = dir_ / "bar.job.yaml", .out_dir = dir_ / out};
    }

    test::TempDir dir_{"planjob"};
};

}  // namespace

TEST_F(PlanJobTest, WritesThePlanDirectoryWithProgressPerStage) {
    std::vector<std::string> stages;
    std::string named;
    const PlanJobResult r = plan_job(request("plan"),
                                     {[&](std::string_view stage, double) {
                                          if (stages.empty() || stages.back() != stage)
                                              stages.emplace_back(stage);
                                      },
                                      nullptr},
                                     [&](const planner::JobSpec& job) { named = job.name; });
    EXPECT_EQ(named, "bar");
    ASSERT_GE(stages.size(), 4u);
    EXPECT_EQ(stages.front(), "read");
    EXPECT_NE(std::find(stages.begin(), stages.end(), "layers"), stages.end());
    EXPECT_EQ(stages[stages.size() - 2], "write");
    EXPECT_EQ(stages.back(), "robot");

    const fs::path out = dir_ / "plan";
    for (const char* f : {"field.vtk", "toolpaths.json", "report.json", "preview/index.html",
                          "rapid/FcChunk0001.mod", "program.json", "print.json", "manifest.json"})
        EXPECT_TRUE(fs::exists(out / f)) << f;
    // The manifest lists every file the plan wrote, and they are as it says.
    const daemon::print::Manifest m = daemon::print::read_manifest(out);
    std::size_t files = 0;
    for (const auto& e : fs::recursive_directory_iterator(out))
        files += e.is_regular_file() && e.path().filename() != "manifest.json";
    EXPECT_EQ(m.files.size(), files);
    EXPECT_TRUE(daemon::print::verify_files(out, m).empty());
    EXPECT_EQ(m.cell, daemon::print::cell_facts(CellConfig{}));
    const auto report = nlohmann::json::parse(read_file(out / "report.json"));
    EXPECT_EQ(report, r.report);
    EXPECT_EQ(report["layers"]["pla"], 1);
    EXPECT_EQ(report["layers"]["ccf"], 1);
    EXPECT_GT(report["fibre"]["paths"].get<int>(), 0);
    EXPECT_GE(report["robot"]["modules"].get<int>(), 1);
    ASSERT_TRUE(r.robot);
    EXPECT_EQ(report["robot"]["moves"].get<std::size_t>(), r.robot->program.moves.size());
    EXPECT_EQ(planner::read_toolpaths_json((out / "toolpaths.json").string()).layers.size(), 2u);
}

TEST_F(PlanJobTest, CancelStopsThePlanAndWritesNoReport) {
    planner::CancelToken cancel;
    const planner::StepControl control{[&](std::string_view stage, double) {
                                           if (stage == "layers") cancel.cancel();
                                       },
                                       &cancel};
    EXPECT_THROW(plan_job(request("plan"), control), planner::Cancelled);
    EXPECT_FALSE(fs::exists(dir_ / "plan" / "report.json"));
    EXPECT_FALSE(fs::exists(dir_ / "plan" / "rapid"));
    EXPECT_FALSE(fs::exists(dir_ / "plan" / "manifest.json"));
}

TEST_F(PlanJobTest, ASettingTheCellCannotPrintRefusesTheJobBeforeAnyWork) {
    std::ofstream(dir_ / "hot.job.yaml")
        << "name: hot\nmodel:\n  mesh: bar.vtk\nprocess:\n  pla: {nozzle_temp_c: 290}\n";
    PlanRequest r = request("hot");
    r.job_file = dir_ / "hot.job.yaml";
    try {
        plan_job(r);
        FAIL() << "expected a refusal";
    } catch (const daemon::print::SettingsError& e) {
        EXPECT_NE(std::string(e.what()).find("process.pla.nozzle_temp_c: 290 degC is above the "
                                             "cell's limit 260 degC (extruder.pla.max_temp_c)"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(fs::exists(dir_ / "hot"));
}

TEST_F(PlanJobTest, APlanThatWouldPrintNothingIsRefused) {
    // A stressed needle thinner than the PLA line (0.4 x 0.4 mm): layers, but no toolpath.
    const auto mesh = planner::structured_tet_mesh({.size = {0.4, 0.4, 4}, .cells = {1, 1, 4}});
    std::vector<planner::StressTensor> stress(mesh.tet_count(), planner::StressTensor::Zero());
    for (auto& t : stress) t(2, 2) = 10.0;
    test::write_vtk_file(dir_ / "needle.vtk", mesh, {.stress = &stress});
    std::ofstream(dir_ / "needle.job.yaml") << "name: needle\nmodel:\n  mesh: needle.vtk\n";
    PlanRequest r = request("needle");
    r.job_file = dir_ / "needle.job.yaml";
    try {
        plan_job(r);
        FAIL() << "a plan with nothing to print was written";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("nothing to print"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir_ / "needle" / "manifest.json"));  // never a finished plan
}

TEST_F(PlanJobTest, FieldStageAloneAndBadJobsFailWithTheirReason) {
    PlanRequest r = request("field");
    r.last_stage = PlanStage::field;
    r.strategy = planner::Strategy::contour_zigzag;
    const PlanJobResult p = plan_job(r);
    EXPECT_EQ(p.job.planner.strategy, planner::Strategy::contour_zigzag);
    EXPECT_FALSE(p.layers);
    EXPECT_FALSE(p.robot);
    EXPECT_TRUE(fs::exists(dir_ / "field" / "field.vtk"));
    EXPECT_TRUE(fs::exists(dir_ / "field" / "report.json"));
    EXPECT_FALSE(fs::exists(dir_ / "field" / "toolpaths.json"));

    std::ofstream(dir_ / "bad.job.yaml") << "name: bad\nmodel:\n  mesh: missing.vtk\n";
    PlanRequest bad = request("bad");
    bad.job_file = dir_ / "bad.job.yaml";
    try {
        plan_job(bad);
        FAIL() << "expected an error";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("model.mesh: file not found"), std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(fs::exists(dir_ / "bad"));
}

TEST_F(PlanJobTest, CommandLineWritesWhatTheLibraryWrites) {
    plan_job(request("library"));
    const std::string cmd = fibrecell::test::binary_path("tools/fibrecell plan ") +
                            (dir_ / "bar.job.yaml").string() + " --threads 2 --out " +
                            (dir_ / "cli").string() + " > " + (dir_ / "stdout.txt").string() +
                            " 2> " + (dir_ / "stderr.txt").string();
    ASSERT_EQ(std::system(cmd.c_str()), 0) << read_file(dir_ / "stderr.txt");
    EXPECT_EQ(read_file(dir_ / "cli" / "toolpaths.json"),
              read_file(dir_ / "library" / "toolpaths.json"));
    EXPECT_EQ(read_file(dir_ / "cli" / "rapid" / "FcChunk0001.mod"),
              read_file(dir_ / "library" / "rapid" / "FcChunk0001.mod"));
    const std::string out = read_file(dir_ / "stdout.txt");
    for (const char* line :
         {"model      450 tets", "layers     1 PLA + 1 CCF", "robot      ", "wrote      "})
        EXPECT_NE(out.find(line), std::string::npos) << line << "\n" << out;
    EXPECT_EQ(read_file(dir_ / "stderr.txt").rfind("planning bar (", 0), 0u);
}

// A model with its own stress and the load case the job states: the plan predicts the part's
// stiffness with and without its fibre (report, preview, CLI), and `fibrecell compare` sets the
// strategies side by side.
TEST_F(PlanJobTest, ALoadCaseGivesThePredictedStiffnessInReportPreviewAndCommandLine) {
    std::ofstream(dir_ / "loaded.job.yaml")
        << "name: loaded\nmodel:\n  mesh: bar.vtk\n"
           "regions:\n  x0: {box: {min: [-1, -1, -1], max: [0.001, 7, 1]}}\n"
           "  x50: {box: {min: [49.999, -1, -1], max: [51, 7, 1]}}\n"
           "analysis:\n  load_case:\n    supports: [x0]\n"
           "    loads: [{region: x50, force_n: [144, 0, 0]}]\n";
    std::vector<std::string> stages;
    const PlanJobResult r = plan_job({.job_file = dir_ / "loaded.job.yaml", .out_dir = dir_ / "m"},
                                     {[&](std::string_view stage, double) {
                                          if (stages.empty() || stages.back() != stage)
                                              stages.emplace_back(stage);
                                      },
                                      nullptr});
    EXPECT_NE(std::find(stages.begin(), stages.end(), "mechanics"), stages.end());
    ASSERT_TRUE(r.mechanics);
    const auto& m = r.report["mechanics"];
    EXPECT_GT(m["reinforced"]["stiffness_n_per_mm"].get<double>(),
              m["bare"]["stiffness_n_per_mm"].get<double>());
    EXPECT_DOUBLE_EQ(m["stiffness_gain"].get<double>(), r.mechanics->prediction.gain());
    EXPECT_NEAR(m["fibre"]["placed_m"].get<double>(), r.report["fibre"]["length_m"].get<double>(),
                1e-6);
    EXPECT_GT(r.report["timings_s"]["mechanics"].get<double>(), 0);
    EXPECT_TRUE(fs::exists(dir_ / "m" / "preview" / "reinforced_stress.svg"));
    EXPECT_NE(read_file(dir_ / "m" / "preview" / "index.html").find("reinforced_stress.svg"),
              std::string::npos);

    // Switched off, or a job with no load case: no prediction.
    PlanRequest off{.job_file = dir_ / "loaded.job.yaml", .out_dir = dir_ / "off"};
    off.mechanics = false;
    EXPECT_FALSE(plan_job(off).report.contains("mechanics"));
    EXPECT_FALSE(plan_job(request("plain")).report.contains("mechanics"));

    const std::string cmd = fibrecell::test::binary_path("tools/fibrecell compare ") +
                            (dir_ / "loaded.job.yaml").string() + " --threads 2 --out " +
                            (dir_ / "cmp").string() + " > " + (dir_ / "cmp.txt").string() + " 2> " +
                            (dir_ / "cmp.err").string();
    ASSERT_EQ(std::system(cmd.c_str()), 0) << read_file(dir_ / "cmp.err");
    const std::string out = read_file(dir_ / "cmp.txt");
    for (const char* line : {"stiffness [N/mm]", "contour-zigzag", "vs no fibre", "compare.json"})
        EXPECT_NE(out.find(line), std::string::npos) << line << "\n" << out;
    const auto c = nlohmann::json::parse(read_file(dir_ / "cmp" / "compare.json"));
    EXPECT_EQ(c["format"], "fibrecell.compare/1");
    EXPECT_DOUBLE_EQ(c["field"]["stiffness_n_per_mm"].get<double>(),
                     m["reinforced"]["stiffness_n_per_mm"].get<double>());
    EXPECT_TRUE(fs::exists(dir_ / "cmp" / "contour-zigzag" / "manifest.json"));

    // Without a load case compare says what it needs.
    const std::string bad = fibrecell::test::binary_path("tools/fibrecell compare ") +
                            (dir_ / "bar.job.yaml").string() + " --out " +
                            (dir_ / "nocase").string() + " > /dev/null 2> " +
                            (dir_ / "nocase.err").string();
    EXPECT_NE(std::system(bad.c_str()), 0);
    EXPECT_NE(read_file(dir_ / "nocase.err").find("no load case"), std::string::npos)
        << read_file(dir_ / "nocase.err");
}
