// The plan directory is the print: what planning writes (rapid/, program.json, print.json, the
// manifest last) is exactly what load_print_plan gives the print, checked by reading the files
// back independently; a changed byte makes the plan damaged, a changed cell fact makes it
// outdated, a missing manifest makes it incomplete, and each refuses the print with what is
// wrong. A re-entry rewrites only the interrupted chunk and takes the later ones as planned.
#include "daemon/print/manifest.hpp"
#include "daemon/print/plan_writer.hpp"
#include "daemon/print/print_plan.hpp"
#include "daemon/print/program_file.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/project_paths.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

using namespace fibrecell;
using namespace fibrecell::daemon::print;
using fibrecell::daemon::CellConfig;
using ::testing::HasSubstr;
namespace abb = drivers::abb;
namespace fs = std::filesystem;

namespace {

// PLA layer 0 (a square), CCF layers 1 and 3 (straight fibres), PLA layer 2: several chunks at a
// small line limit.
std::vector<planner::ToolpathLayer> small_part() {
    using planner::Head;
    using planner::PathRole;
    std::vector<planner::ToolpathLayer> layers;
    for (int i = 0; i < 4; ++i) {
        const bool pla = i % 2 == 0;
        planner::ToolpathLayer l{.index = i, .z = 0.8 + 0.05 * i, .head = pla ? Head::pla : Head::ccf,
                                 .thickness = pla ? 0.8 : 0.05};
        if (pla) {
            l.paths.push_back({PathRole::perimeter, true, {{120, 140}, {140, 140}, {140, 160}, {120, 160}}});
        } else {
            for (double y : {145.0, 150.0, 155.0}) {
                planner::Toolpath p{PathRole::fibre, false, {}};
                for (int k = 0; k <= 10; ++k) p.points.emplace_back(100 + 10 * k, y);
                l.paths.push_back(p);
            }
        }
        layers.push_back(l);
    }
    return layers;
}

class PlanFilesTest : public ::testing::Test {
  protected:
    void SetUp() override {
        cell_.robot.rapid.max_chunk_lines = 60;
        settings_ = print_settings(planner::parse_job("name: part\nmodel: {mesh: loop.msh}\n",
                                                      "part.job.yaml",
                                                      fibrecell::test::source_path("examples/loop"),
                                                      planner::JobFiles::anywhere),
                                   cell_);
        plan_ = plan_robot(small_part(), cell_.robot, settings_, "part");
        PlanWriter out(dir_);
        out.write("toolpaths.json", "{}\n");
        write_print_files(out, plan_, {.job = "part", .strategy = "field", .layers = 4,
                                       .settings = settings_});
        out.finish("part", cell_facts(cell_));
    }
    std::string refusal(const CellConfig& cell) const {
        try {
            load_print_plan(dir_, cell);
        } catch (const PlanRefused& e) {
            return e.what();
        }
        return "";
    }

    fibrecell::test::TempDir tmp_{"plan-files"};
    const fs::path dir_ = tmp_.path();
    CellConfig cell_;
    PrintSettings settings_;
    RobotPlan plan_;
};

}  // namespace

TEST_F(PlanFilesTest, TheManifestListsEveryFileWithItsSizeAndSha256) {
    ASSERT_GE(plan_.rapid.modules.size(), 3u);
    const Manifest m = read_manifest(dir_);
    EXPECT_EQ(m.job, "part");
    EXPECT_EQ(m.cell, cell_facts(cell_));
    // Every file but the manifest is listed, and the system's sha256sum agrees with each entry.
    std::size_t files = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir_))
        files += e.is_regular_file() && e.path().filename() != manifest_name;
    EXPECT_EQ(m.files.size(), files);
    std::ofstream check(dir_ / "check.sha256");
    for (const ManifestEntry& e : m.files) {
        check << e.sha256 << "  " << e.path << "\n";
        EXPECT_EQ(fs::file_size(dir_ / e.path), e.bytes) << e.path;
    }
    check.close();
    const std::string cmd = "cd " + dir_.string() + " && sha256sum --quiet -c check.sha256";
    EXPECT_EQ(std::system(cmd.c_str()), 0);
}

TEST_F(PlanFilesTest, ThePrintGetsExactlyWhatWasPlanned) {
    const PrintPlan p = load_print_plan(dir_, cell_);
    EXPECT_EQ(p.first_chunk, 1);
    EXPECT_EQ(p.chunk_count, static_cast<int>(plan_.rapid.modules.size()));
    ASSERT_EQ(p.chunks.size(), plan_.rapid.modules.size());
    for (std::size_t c = 0; c < p.chunks.size(); ++c) {
        EXPECT_EQ(p.chunks[c].file_name, plan_.rapid.modules[c].file_name);
        EXPECT_EQ(p.chunks[c].text, fibrecell::test::read_file(dir_ / "rapid" / p.chunks[c].file_name));
        EXPECT_EQ(p.chunks[c].text, plan_.rapid.modules[c].text);
    }
    EXPECT_EQ(to_json(p.print.settings), to_json(settings_));
    EXPECT_EQ(p.layers(), 4u);
    // program.json holds the program exactly: written again, it is the same text.
    EXPECT_EQ(program_json_text(p.program, p.joints), fibrecell::test::read_file(dir_ / "program.json"));
    ASSERT_EQ(p.program.events.size(), plan_.program.events.size());
    for (std::size_t i = 0; i < p.program.events.size(); ++i) {
        EXPECT_EQ(p.program.events[i].kind, plan_.program.events[i].kind);
        EXPECT_EQ(p.program.events[i].move, plan_.program.events[i].move);
        EXPECT_EQ(p.program.events[i].length_mm, plan_.program.events[i].length_mm);
    }
    EXPECT_EQ(p.joints, plan_.rapid.joints);
}

TEST_F(PlanFilesTest, AChangedByteMakesThePlanDamaged) {
    const fs::path chunk = dir_ / "rapid" / "FcChunk0002.mod";
    std::string text = fibrecell::test::read_file(chunk);
    text[text.size() / 2] ^= 1;
    std::ofstream(chunk, std::ios::binary) << text;
    EXPECT_THAT(refusal(cell_), HasSubstr("the plan is damaged (rapid/FcChunk0002.mod: sha256 "
                                          "differs from the manifest); replan the job"));
    std::ofstream(dir_ / "program.json", std::ios::app) << " ";
    EXPECT_THAT(refusal(cell_), HasSubstr("program.json: "));
    fs::remove(dir_ / "print.json");
    EXPECT_THAT(refusal(cell_), HasSubstr("print.json: missing"));
}

TEST_F(PlanFilesTest, APlanWithoutItsManifestIsIncomplete) {
    fs::remove(dir_ / manifest_name);
    EXPECT_THAT(refusal(cell_), HasSubstr("the plan has no manifest.json: it is incomplete"));
    // A new plan in the same folder first removes what the old one wrote.
    PlanWriter again(dir_);
    EXPECT_FALSE(fs::exists(dir_ / "rapid"));
}

TEST_F(PlanFilesTest, AChangedCellFactRefusesThePrintNamingIt) {
    CellConfig moved = cell_;
    moved.robot.bed.translation().x() += 10;
    EXPECT_THAT(refusal(moved), HasSubstr("the cell changed since the job was planned "
                                          "(robot.bed.position_mm: [380.0,-150.0,100.0] when "
                                          "planned, [390.0,-150.0,100.0] now)"));
    CellConfig cutter = cell_;
    cutter.extruder.cutter_distance_mm = 40;
    EXPECT_THAT(refusal(cutter), HasSubstr("extruder.ccf.cutter_distance_mm: 42.0 when planned, 40.0 now"));
    CellConfig tilt = cell_;
    tilt.robot.head.tilt_deg = 14;
    EXPECT_THAT(refusal(tilt), HasSubstr("robot.head.tilt_deg"));
    // What a plan does not depend on may change: the board's port, the robot's address.
    CellConfig moved_link = cell_;
    moved_link.extruder.link.serial.device = "/dev/ttyACM0";
    moved_link.rws.client.port = 8080;
    EXPECT_EQ(refusal(moved_link), "");
}

TEST_F(PlanFilesTest, AReentryRewritesOnlyTheInterruptedChunk) {
    const std::size_t chunks = plan_.rapid.modules.size();
    // The last fibre path's cut not confirmed: re-enter at that path, in the last chunk that
    // holds its travel.
    const auto& events = plan_.program.events;
    std::int64_t last_fibre_start = 0;
    for (const auto& e : events)
        if (e.kind == abb::EventKind::fibre_start) last_fibre_start = e.sequence;
    const PrintPlan p = load_print_plan(dir_, cell_, last_fibre_start);
    ASSERT_TRUE(p.resume);
    EXPECT_EQ(p.first_event, last_fibre_start);
    const std::size_t travel = p.resume->first_move - 1;
    std::size_t c = 0;
    while (!(travel >= plan_.rapid.modules[c].first_move && travel < plan_.rapid.modules[c].end_move)) ++c;
    EXPECT_EQ(p.first_chunk, static_cast<int>(c) + 1);
    EXPECT_EQ(p.chunk_count, static_cast<int>(chunks));
    ASSERT_EQ(p.chunks.size(), chunks - c);
    // The rewritten chunk keeps its name, starts with the lift, fits the limit; the later ones
    // are the planned files, byte for byte.
    EXPECT_EQ(p.chunks[0].file_name, plan_.rapid.modules[c].file_name);
    EXPECT_THAT(p.chunks[0].text, HasSubstr("MoveL Offs(CRobT("));
    EXPECT_LE(static_cast<std::size_t>(std::count(p.chunks[0].text.begin(), p.chunks[0].text.end(), '\n')),
              static_cast<std::size_t>(cell_.robot.rapid.max_chunk_lines));
    EXPECT_NE(p.chunks[0].text, plan_.rapid.modules[c].text);
    for (std::size_t k = 1; k < p.chunks.size(); ++k)
        EXPECT_EQ(p.chunks[k].text, fibrecell::test::read_file(dir_ / "rapid" / plan_.rapid.modules[c + k].file_name));
    // Nothing left: no chunk at all.
    const PrintPlan done = load_print_plan(dir_, cell_, static_cast<std::int64_t>(events.size()));
    ASSERT_TRUE(done.resume);
    EXPECT_TRUE(done.resume->nothing_left);
    EXPECT_TRUE(done.chunks.empty());
}

TEST_F(PlanFilesTest, AFibrePathReentersWhereItsFeedEnded) {
    // The last fibre path (y = 155 from x = 100 to 200; its collinear points merged, so one move
    // to the cut point at x = 158, 42 mm before the end, and one to the end) with 25 mm fed: the
    // run rises above x = 125, comes down there, waits for the new thread and goes on.
    const auto& events = plan_.program.events;
    std::int64_t s = 0;
    for (const auto& e : events)
        if (e.kind == abb::EventKind::fibre_start) s = e.sequence;
    const ResumePoint r = resume_point(plan_.program, s, FibreFed{s, 25.0});
    ASSERT_DOUBLE_EQ(r.fibre_fed_mm, 25.0);
    const abb::PrintProgram run = reentry_program(plan_.program, r);
    ASSERT_GE(run.moves.size(), 4u);
    const abb::ProgramMove& travel = plan_.program.moves[r.first_move - 1];
    EXPECT_EQ(run.moves[0].role, abb::MoveRole::travel);
    EXPECT_NEAR(run.moves[0].position_mm.x(), 125, 1e-9);
    EXPECT_NEAR(run.moves[0].position_mm.y(), 155, 1e-9);
    EXPECT_NEAR(run.moves[0].position_mm.z(), travel.position_mm.z(), 1e-9);
    EXPECT_EQ(run.moves[1].role, abb::MoveRole::approach);
    EXPECT_TRUE(run.moves[1].fine);
    EXPECT_NEAR(run.moves[1].position_mm.x(), 125, 1e-9);
    EXPECT_NEAR(run.moves[1].position_mm.z(), plan_.program.moves[r.first_move].position_mm.z(), 1e-9);
    EXPECT_EQ(run.moves[2].role, abb::MoveRole::print);
    EXPECT_NEAR(run.moves[2].position_mm.x(), 158, 1e-9);
    EXPECT_NEAR(run.moves[2].length_mm, 33, 1e-9);
    ASSERT_FALSE(run.events.empty());
    EXPECT_EQ(run.events[0].sequence, s);
    EXPECT_EQ(run.events[0].kind, abb::EventKind::fibre_start);
    EXPECT_EQ(run.events[0].move, 2u);
    EXPECT_EQ(run.events[0].anchor, abb::EventAnchor::before);
    // The cut at x = 158 stays where it was on the part: at the end of that move.
    ASSERT_GE(run.events.size(), 2u);
    EXPECT_EQ(run.events[1].kind, abb::EventKind::cut);
    EXPECT_EQ(run.events[1].move, 2u);
    EXPECT_NEAR(run.events[1].position_mm.x(), 158, 1e-9);
    // Loaded as a plan, the rewritten chunk is the one holding x = 125's move, with the lift.
    const PrintPlan p = load_print_plan(dir_, cell_, s, FibreFed{s, 25.0});
    ASSERT_TRUE(p.resume);
    EXPECT_EQ(p.first_event, s);
    EXPECT_THAT(p.chunks[0].text, HasSubstr("MoveL Offs(CRobT("));
    EXPECT_THAT(p.chunks[0].text, HasSubstr("125"));
}
