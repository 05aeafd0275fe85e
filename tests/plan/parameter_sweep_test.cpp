// A planner setting swept over one field stage (the paper's Fig. 9): parsing the request, the
// points against plans made one by one, and `fibrecell plan --sweep` end to end.

#include "planner/plan/parameter_sweep.hpp"
#include "planner/mesh/structured_mesh.hpp"
#include "tests/support/plan_inputs.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/project_paths.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

using namespace fibrecell::planner;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

std::string parse_error(const std::string& text) {
    try {
        parse_sweep(text);
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "(no error)";
}

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

class ParameterSweepTest : public ::testing::Test {
  protected:
    void SetUp() override {
        // 100 x 20 x 1.6 mm bar pulled along x, nine times harder at y = 20 than at y = 0: two
        // CCF layers whose spacing depends on p.
        const TetMesh mesh = structured_tet_mesh({.size = {100, 20, 1.6}, .cells = {50, 10, 2}});
        std::vector<StressTensor> stress(mesh.tet_count(), StressTensor::Zero());
        for (std::size_t t = 0; t < stress.size(); ++t) {
            const double y =
                (mesh.vertices[mesh.tets[t][0]].y() + mesh.vertices[mesh.tets[t][1]].y() +
                 mesh.vertices[mesh.tets[t][2]].y() + mesh.vertices[mesh.tets[t][3]].y()) /
                4;
            stress[t](0, 0) = 10.0 + 4.0 * y;
        }
        fibrecell::test::write_vtk_file(dir_ / "bar.vtk", mesh, {.stress = &stress});
        std::ofstream(dir_ / "bar.job.yaml") << "name: bar\nmodel:\n  mesh: bar.vtk\n"
                                                "placement:\n  position_mm: [50, 10]\n";
    }

    fibrecell::test::TempDir dir_{"sweep"};
};

}  // namespace

TEST(ParseSweep, NameAndValues) {
    const ParameterSweep s = parse_sweep("p=0,0.5,1,2");
    EXPECT_EQ(s.parameter, "p");
    EXPECT_EQ(s.values, (std::vector<double>{0, 0.5, 1, 2}));
    EXPECT_EQ(parse_sweep("sigma_cap_percentile=95,100").values.size(), 2u);
    EXPECT_TRUE(s.points.empty());
}

TEST(ParseSweep, ErrorsSayWhatIsWrong) {
    EXPECT_THAT(parse_error("p"), HasSubstr("expected NAME=V1,V2"));
    EXPECT_THAT(parse_error("q=1,2"), HasSubstr("unknown parameter 'q' (one of p, "));
    EXPECT_THAT(parse_error("p=1,,2"), HasSubstr("'' is not a number"));
    EXPECT_THAT(parse_error("p=1,x"), HasSubstr("'x' is not a number"));
    EXPECT_THAT(parse_error("p=11"), HasSubstr("p = 11 is outside [0"));
    EXPECT_THAT(parse_error("sigma_cap_percentile=0"), HasSubstr("is outside (0"));
    std::string seventeen = "p=1";
    for (int i = 0; i < 16; ++i) seventeen += ",1";
    EXPECT_THAT(parse_error(seventeen), HasSubstr("at most 16 values, not 17"));
}

TEST_F(ParameterSweepTest, EachPointIsThePlanOfThatValue) {
    const JobSpec job = load_job_file((dir_ / "bar.job.yaml").string());
    const FieldStageResult field = fibrecell::test::field_stage_of(job);
    ParameterSweep sweep = parse_sweep("p=0,2");
    std::vector<double> progress;
    run_sweep(sweep, job, field, {.cutter_distance_mm = 0},
              {[&](std::string_view stage, double f) {
                   EXPECT_EQ(stage, "sweep");
                   progress.push_back(f);
               },
               nullptr});
    ASSERT_EQ(sweep.points.size(), 2u);
    ASSERT_FALSE(progress.empty());
    EXPECT_TRUE(std::is_sorted(progress.begin(), progress.end()));
    EXPECT_DOUBLE_EQ(progress.back(), 1.0);
    for (const SweepPoint& point : sweep.points) {
        JobSpec alone = job;
        alone.planner.p = point.value;
        const LayerStageStats s = run_layer_stage(alone, field, {.cutter_distance_mm = 0}).stats;
        EXPECT_DOUBLE_EQ(point.fibre_length_mm, s.fibre_length_mm) << "p = " << point.value;
        EXPECT_EQ(point.fibre_paths, s.fibre_paths);
        EXPECT_DOUBLE_EQ(point.density_correlation, s.quality.density_correlation());
    }
    // Uniform spacing (p = 0) is set by the part; p = 2 spreads the paths where sigma is low.
    EXPECT_GT(sweep.points[0].fibre_length_mm, sweep.points[1].fibre_length_mm);
}

TEST_F(ParameterSweepTest, CommandLineWritesTheSweepIntoReportAndPreview) {
    const fs::path out = dir_ / "plan";
    const std::string log = (dir_ / "out.txt").string();
    const std::string plan = fibrecell::test::binary_path("tools/fibrecell plan ") +
                             (dir_ / "bar.job.yaml").string() + " --out " + out.string();
    ASSERT_EQ(std::system((plan + " --sweep p=0,1,2 > " + log + " 2>&1").c_str()), 0)
        << std::ifstream(log).rdbuf();
    std::ifstream in(out / "report.json");
    const auto report = nlohmann::json::parse(in);
    EXPECT_EQ(report["sweep"]["parameter"], "p");
    const auto& points = report["sweep"]["points"];
    ASSERT_EQ(points.size(), 3u);
    // The job's own p is 1: that point is the plan itself.
    EXPECT_EQ(points[1]["value"], 1.0);
    EXPECT_DOUBLE_EQ(points[1]["fibre_length_m"].get<double>(),
                     report["fibre"]["length_m"].get<double>());
    std::stringstream svg, index;
    svg << std::ifstream(out / "preview" / "sweep.svg").rdbuf();
    index << std::ifstream(out / "preview" / "index.html").rdbuf();
    EXPECT_EQ(count(svg.str(), "<circle class=\"point\""), 3u);
    EXPECT_EQ(count(index.str(), "src=\"sweep.svg\""), 1u);
    EXPECT_EQ(count(index.str(), "src=\"neighbour_dots.svg\""), 1u);

    // A bad request names itself and writes nothing.
    ASSERT_NE(std::system((plan + "-bad --sweep q=1 > " + log + " 2>&1").c_str()), 0);
    std::stringstream text;
    text << std::ifstream(log).rdbuf();
    EXPECT_THAT(text.str(), HasSubstr("fibrecell plan: sweep: unknown parameter 'q'"));
    EXPECT_FALSE(fs::exists(dir_ / "plan-bad" / "report.json"));
}
