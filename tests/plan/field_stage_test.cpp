// The field stage end to end: a job file pointing at a mesh with a known stress field, run through
// the library and through the real `fibrecell plan` executable.

#include "planner/plan/field_stage.hpp"
#include "planner/io/read_model.hpp"
#include "planner/io/vtk_writer.hpp"
#include "planner/job/job_spec.hpp"
#include "planner/mesh/adjacency.hpp"
#include "planner/mesh/structured_mesh.hpp"
#include "tests/support/plan_inputs.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/project_paths.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

using namespace fibrecell::planner;
namespace fs = std::filesystem;

namespace {

class FieldStageTest : public ::testing::Test {
  protected:
    // A 20 x 10 x 2 mm bar in uniaxial tension along x, except a block in pure compression
    // (rule 3) at x < 4; eigen-solver signs are whatever they are. With `odd`, one tet in the
    // middle is pulled along y instead (odd_), against all its neighbours.
    std::string write_bar(bool odd = false) {
        mesh_ = structured_tet_mesh({.size = {20, 10, 2}, .cells = {10, 5, 1}});
        for (const Tet& t : mesh_.tets) {
            const double x = (mesh_.vertices[t[0]] + mesh_.vertices[t[1]] + mesh_.vertices[t[2]] +
                              mesh_.vertices[t[3]])
                                 .x() /
                             4;
            StressTensor s = StressTensor::Zero();
            s(0, 0) = x < 4 ? -50.0 : 50.0;
            if (odd && odd_ < 0 && x > 10) {
                odd_ = static_cast<int>(stress_.size());
                s(0, 0) = 0, s(1, 1) = 50.0;
            }
            stress_.push_back(s);
        }
        const std::string path = (dir_ / "bar.vtk").string();
        fibrecell::test::write_vtk_file(path, mesh_, {.stress = &stress_});
        return path;
    }

    void write_job(const std::string& extra = "") {
        std::ofstream(dir_ / "bar.job.yaml") << "name: bar\nmodel:\n  mesh: bar.vtk\n" << extra;
    }

    fibrecell::test::TempDir dir_{"field"};
    TetMesh mesh_;
    std::vector<StressTensor> stress_;
    int odd_ = -1;
};

}  // namespace

TEST_F(FieldStageTest, UniaxialBarGivesAConsistentFieldAlongX) {
    write_bar();
    write_job();
    const FieldStageResult r =
        fibrecell::test::field_stage_of(load_job_file((dir_ / "bar.job.yaml").string()));
    ASSERT_EQ(r.field.v_e.size(), mesh_.tet_count());
    EXPECT_FALSE(r.fea);
    EXPECT_EQ(r.mst.components, 1);
    std::size_t compressed = 0;
    for (std::size_t e = 0; e < r.field.v_e.size(); ++e) {
        // All along x, and after re-orientation all with one sign.
        EXPECT_NEAR(std::abs(r.field.v_e[e].x()), 1.0, 1e-9);
        EXPECT_EQ(r.field.v_e[e].x() > 0, r.field.v_e[0].x() > 0) << "element " << e;
        if (r.field.rule[e] == TensileRule::no_tension) {
            ++compressed;
            EXPECT_DOUBLE_EQ(r.field.sigma_e[e], 1e-5);
        } else {
            EXPECT_DOUBLE_EQ(r.field.sigma_e[e], 50.0);
        }
    }
    EXPECT_EQ(compressed, 2u * 5 * 6);  // the 2 x 5 cells left of x = 4
    EXPECT_EQ(r.removed, 0u);
}

TEST_F(FieldStageTest, FieldProcessingCanBeSwitchedOffForTheAblation) {
    write_bar(/*odd=*/true);
    ASSERT_GE(odd_, 0);
    const auto plan = [&](const std::string& planner) {
        write_job(planner);
        return fibrecell::test::field_stage_of(load_job_file((dir_ / "bar.job.yaml").string()));
    };
    // As the paper does it: one tree, the odd element's direction undefined, and the histogram
    // puts exactly its pairs (at dot 0) at or below eta.
    const FieldStageResult on = plan("");
    EXPECT_EQ(on.mst.components, 1);
    EXPECT_EQ(on.removed, 1u);
    EXPECT_EQ(on.v_defined[odd_], 0);
    const auto odd_pairs = vertex_sharing_neighbours(mesh_).neighbours(odd_).size();
    EXPECT_EQ(on.neighbour_dots.at_most_eta, odd_pairs);
    EXPECT_EQ(on.neighbour_dots.counts[10], odd_pairs);  // the bin [0, 0.1)

    // Both steps off: no tree, no sign changed, every direction kept.
    const FieldStageResult off =
        plan("planner:\n  mst_reorientation: false\n  incompatibility_removal: false\n");
    EXPECT_EQ(off.mst.components, 0);
    EXPECT_EQ(off.mst.flipped, 0);
    EXPECT_TRUE(off.mst.parent.empty());
    EXPECT_EQ(off.removed, 0u);
    EXPECT_EQ(std::count(off.v_defined.begin(), off.v_defined.end(), 0), 0);
    ASSERT_EQ(off.field.v_e.size(), on.field.v_e.size());
    for (std::size_t e = 0; e < off.field.v_e.size(); ++e)  // the same axes, signs as solved
        EXPECT_NEAR(std::abs(off.field.v_e[e].dot(on.field.v_e[e])), 1.0, 1e-9) << e;
}

TEST_F(FieldStageTest, FailsClearlyWithoutStress) {
    mesh_ = structured_tet_mesh({.size = {2, 2, 2}, .cells = {1, 1, 1}});
    fibrecell::test::write_vtk_file(dir_ / "bar.vtk", mesh_, {});
    write_job();
    try {
        fibrecell::test::field_stage_of(load_job_file((dir_ / "bar.job.yaml").string()));
        FAIL() << "expected an error";
    } catch (const std::exception& e) {
        EXPECT_THAT(e.what(), ::testing::HasSubstr("carries no stress field"));
    }
}

TEST_F(FieldStageTest, CommandLineWritesFieldVtkAndReport) {
    write_bar();
    write_job();
    const fs::path out = dir_ / "plan";
    const std::string cmd = fibrecell::test::binary_path("tools/fibrecell plan ") +
                            (dir_ / "bar.job.yaml").string() + " --out " + out.string() +
                            " --stage field > " + (dir_ / "stdout.txt").string() + " 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << std::ifstream(dir_ / "stdout.txt").rdbuf();

    std::ifstream report_file(out / "report.json");
    const auto report = nlohmann::json::parse(report_file);
    EXPECT_EQ(report["format"], "fibrecell.report/1");
    EXPECT_EQ(report["model"]["tets"], mesh_.tet_count());
    EXPECT_EQ(report["model"]["vertices"], mesh_.vertex_count());
    for (const char* key :
         {"read", "fea", "principal", "mst_reorientation", "incompatible_removal", "total"})
        EXPECT_TRUE(report["timings_s"][key].is_number()) << key;
    EXPECT_EQ(report["timings_s"]["fea"], 0.0);
    // A uniform field: no reading of Eq. 2 undefines anything.
    for (const char* rule : {"all", "majority", "any"})
        EXPECT_EQ(report["field"]["v_undefined_fraction_by_rule"][rule], 0.0) << rule;

    // field.vtk reads back with the mesh and the stress it was given.
    const VolumeModel back = read_volume_model((out / "field.vtk").string());
    EXPECT_EQ(back.mesh.tet_count(), mesh_.tet_count());
    ASSERT_TRUE(back.stress);
    EXPECT_EQ((*back.stress)[17], stress_[17]);
}

TEST_F(FieldStageTest, CommandLineNamesTheBadKeyAndFails) {
    write_bar();
    write_job("planner:\n  eta: 7\n");
    const std::string log = (dir_ / "stderr.txt").string();
    const std::string cmd = fibrecell::test::binary_path("tools/fibrecell plan ") +
                            (dir_ / "bar.job.yaml").string() + " --out " +
                            (dir_ / "plan").string() + " 2> " + log;
    EXPECT_NE(std::system(cmd.c_str()), 0);
    std::stringstream text;
    text << std::ifstream(log).rdbuf();
    EXPECT_THAT(text.str(), ::testing::HasSubstr("line 5: planner.eta: must be in [-1, 1], got 7"));
    EXPECT_FALSE(fs::exists(dir_ / "plan" / "report.json"));
}
