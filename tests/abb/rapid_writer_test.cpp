// The RAPID chunk writer, tested by reading the generated modules back with the project's RAPID
// reader and checking invariants: every chunk validates, every print target is its toolpath point
// (through the work object and the tool), the head tilt is +-15 deg for the active nozzle, each cut
// lies the cutter distance before its fibre path end, every target is reachable with the confdata
// written, chunks stay under the line limit and end at travel stop points, events run 1..N.
#include "drivers/abb/rapid/rapid_writer.hpp"

#include "drivers/abb/kinematics/confdata.hpp"
#include "drivers/abb/kinematics/joint_solver.hpp"
#include "drivers/abb/rapid/reader.hpp"
#include "tests/support/temp_dir.hpp"
#include "head_tilt.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include <unistd.h>

using namespace fibrecell;
using namespace fibrecell::drivers::abb;
using fibrecell::test::signed_tilt_deg;
namespace rapid = fibrecell::drivers::abb::rapid;

namespace {

using std::numbers::pi;

// Two layers: a 20 mm PLA square and an infill line, then a CCF layer with a 100 mm fibre, gently
// curved so that no point merges away (radius 250 mm: 0.05 mm sagitta per 10 mm step), and a
// closed 30 mm fibre ring.
std::vector<RobotLayer> two_layers() {
    RobotLayer pla{.index = 0, .z = 0.8, .nozzle = Nozzle::pla};
    pla.paths.push_back(
        {true, {{140, 140}, {160, 140}, {160, 160}, {140, 160}}});
    pla.paths.push_back({false, {{142, 142}, {158, 158}}});
    RobotLayer ccf{.index = 1, .z = 0.85, .nozzle = Nozzle::ccf};
    RobotPath line{false, {}};
    for (int i = 0; i <= 10; ++i) {
        const double x = 10.0 * i - 50;
        line.points.emplace_back(150 + x, 120 + 0.002 * x * x);
    }
    ccf.paths.push_back(line);
    ccf.paths.push_back(
        {true, {{130, 130}, {160, 130}, {160, 160}, {130, 160}}});
    return {pla, ccf};
}

// One line of a chunk, as far as these tests care.
struct Item {
    enum Kind { trigger, barrier, motion } kind = motion;
    std::size_t line = 0;  // 1-based in its chunk
    long value = 0;        // trigger/barrier: the event number
    std::string var;       // trigger: its triggdata
    bool start = false;    // trigger: \Start
    bool lag = false;      // trigger: TriggEquip
    // motion
    std::string instruction, speed, zone, tool;
    std::vector<std::string> triggers;
    rapid::MoveTarget target;
    int chunk = 0;
};

struct ReadBack {
    std::vector<Item> items;  // every chunk, in order
    std::vector<rapid::Module> modules;
};

rapid::ValidateOptions validate_options(const RobotCellConfig& cell, const std::string& file,
                                        std::size_t max_lines) {
    rapid::ValidateOptions o;
    o.file_name = file;
    o.known_signals = cell.signals.all();
    o.external_routines = {std::string(barrier_routine)};
    o.max_lines = max_lines;
    return o;
}

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(' ');
    return b == std::string::npos ? "" : s.substr(b);
}

bool starts_with(const std::string& s, const std::string& prefix) {
    return s.rfind(prefix, 0) == 0;
}

std::vector<std::string> split(const std::string& s, const std::string& sep) {
    std::vector<std::string> out;
    std::size_t at = 0;
    for (std::size_t k; (k = s.find(sep, at)) != std::string::npos; at = k + sep.size())
        out.push_back(s.substr(at, k - at));
    out.push_back(s.substr(at));
    return out;
}

// "TriggEquip tgFc1, 0 \Start, 0.05 \GOp:=goFcEvent, 17;" / "TriggIO tgFc1, 0 \GOp:=goFcEvent, 2;"
void parse_trigger(const std::string& l, Item& it, const RobotCellConfig& cell) {
    it.kind = Item::trigger;
    it.lag = starts_with(l, "TriggEquip ");
    const std::size_t sp = l.find(' ');
    it.var = l.substr(sp + 1, l.find(',') - sp - 1);
    it.start = l.find("\\Start") != std::string::npos;
    const std::size_t op = l.find("\\GOp:=");
    ASSERT_NE(op, std::string::npos) << l;
    const std::size_t comma = l.find(',', op);
    EXPECT_EQ(l.substr(op + 6, comma - op - 6), cell.signals.event) << l;
    ASSERT_EQ(l.back(), ';');
    it.value = std::stol(l.substr(comma + 2, l.size() - comma - 3));
}

// "TriggL [[..],[..],[..],[..]], vFcPla, tgFc1 \T2:=tgFc2, zFcPrint, tFcPla \WObj:=wFcBed;"
void parse_motion(const std::string& l, Item& it) {
    it.kind = Item::motion;
    it.instruction = l.substr(0, l.find(' '));
    const std::size_t end = l.rfind("]], ");
    ASSERT_NE(end, std::string::npos) << l;
    const std::vector<std::string> parts = split(l.substr(end + 4), ", ");
    ASSERT_TRUE(parts.size() == 3 || parts.size() == 4) << l;
    it.speed = parts[0];
    if (parts.size() == 4) {
        const std::vector<std::string> trig = split(parts[1], " ");
        it.triggers.push_back(trig[0]);
        for (std::size_t k = 1; k < trig.size(); ++k)
            it.triggers.push_back(trig[k].substr(trig[k].find(":=") + 2));
    }
    it.zone = parts[parts.size() - 2];
    const std::string& last = parts.back();
    EXPECT_EQ(last.substr(last.find(' ')), " \\WObj:=wFcBed;") << l;
    it.tool = last.substr(0, last.find(' '));
}

// Reads every chunk back; fails the test on any diagnostic.
ReadBack read_back(const RapidOutput& out, const RobotCellConfig& cell, std::size_t max_lines) {
    ReadBack r;
    for (std::size_t c = 0; c < out.modules.size(); ++c) {
        const RapidModule& m = out.modules[c];
        const rapid::CheckResult check =
            rapid::check_module(m.text, validate_options(cell, m.file_name, max_lines));
        for (const auto& d : check.diagnostics) ADD_FAILURE() << rapid::format(d);
        if (!check.module) {
            ADD_FAILURE() << m.file_name << " did not parse";
            continue;
        }
        r.modules.push_back(*check.module);
        const std::vector<rapid::MoveTarget> targets = rapid::move_targets(*check.module);
        std::size_t next_target = 0;
        std::istringstream in(m.text);
        std::string raw;
        for (std::size_t n = 1; std::getline(in, raw); ++n) {
            const std::string line = trim(raw);
            Item it;
            it.line = n;
            it.chunk = static_cast<int>(c);
            if (starts_with(line, "TriggEquip ") || starts_with(line, "TriggIO ")) {
                parse_trigger(line, it, cell);
            } else if (starts_with(line, std::string(barrier_routine) + " ")) {
                it.kind = Item::barrier;
                it.value = std::stol(line.substr(barrier_routine.size() + 1));
            } else if (starts_with(line, "MoveL ") || starts_with(line, "MoveJ ") ||
                       starts_with(line, "TriggL ") || starts_with(line, "TriggJ ")) {
                parse_motion(line, it);
                EXPECT_LT(next_target, targets.size());
                if (next_target < targets.size()) {
                    it.target = targets[next_target++];
                    EXPECT_EQ(it.target.line, n);
                }
            } else {
                EXPECT_EQ(line.find("Move"), std::string::npos) << line;
                EXPECT_EQ(line.find("Trigg"), std::string::npos) << line;
                continue;
            }
            r.items.push_back(it);
        }
        EXPECT_EQ(next_target, targets.size());
    }
    return r;
}

std::vector<const Item*> motions(const ReadBack& r) {
    std::vector<const Item*> out;
    for (const Item& i : r.items)
        if (i.kind == Item::motion) out.push_back(&i);
    return out;
}

Eigen::Isometry3d to_isometry(const Eigen::Vector3d& t, const Eigen::Quaterniond& q) {
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    p.linear() = q.normalized().toRotationMatrix();
    p.translation() = t;
    return p;
}

// The TCP of a read-back target in the bed frame, recomputed through the arm: IK on the
// robtarget's cfx for the tool and work object as read, FK of the joints, the tool's frame, back
// into the work object. Checks reachability and that the confdata written is the IK's.
Eigen::Vector3d tcp_through_arm(const RobotCellConfig& cell, const rapid::MoveTarget& t,
                                JointVector& reference) {
    EXPECT_TRUE(t.robtarget && t.tool_data && t.wobj_data);
    const rapid::Robtarget& rt = *t.robtarget;
    const Eigen::Isometry3d tool =
        to_isometry(t.tool_data->tframe.trans_mm, t.tool_data->tframe.rot);
    const Eigen::Isometry3d wobj =
        to_isometry(t.wobj_data->uframe.trans_mm, t.wobj_data->uframe.rot) *
        to_isometry(t.wobj_data->oframe.trans_mm, t.wobj_data->oframe.rot);
    const RobotModel robot = cell.model();
    JointSolverOptions o = cell.solver;
    o.cfx = rt.conf.cfx;
    EXPECT_EQ(rt.conf.cfx, cell.solver.cfx);
    EXPECT_NEAR(rt.rot.norm(), 1, 1e-5);
    const IkResult ik = solve_tcp(robot, {.tool = tool, .work_object = wobj},
                                  to_isometry(rt.trans_mm, rt.rot), reference, o);
    EXPECT_TRUE(ik.ok()) << "line " << t.line << ": " << ik.failure.reason;
    if (!ik.ok()) return rt.trans_mm;
    EXPECT_EQ(ik.conf.cf1, rt.conf.cf1) << "line " << t.line;
    EXPECT_EQ(ik.conf.cf4, rt.conf.cf4) << "line " << t.line;
    EXPECT_EQ(ik.conf.cf6, rt.conf.cf6) << "line " << t.line;
    reference = ik.joints;
    const Eigen::Isometry3d tcp_in_bed =
        wobj.inverse() * forward_kinematics(robot.geometry, ik.joints) * tool;
    return tcp_in_bed.translation();
}

// The point `rest` mm of arc length before the end of a toolpath (closed: back at its start).
Eigen::Vector2d before_end(const RobotPath& p, double rest) {
    std::vector<Eigen::Vector2d> pts = p.points;
    if (p.closed) pts.push_back(pts.front());
    for (std::size_t i = pts.size() - 1; i > 0; --i) {
        const double seg = (pts[i] - pts[i - 1]).norm();
        if (seg >= rest) return pts[i] + (rest / seg) * (pts[i - 1] - pts[i]);
        rest -= seg;
    }
    return pts.front();
}

struct Generated {
    std::vector<RobotLayer> layers;
    PrintProgram program;
    RapidOutput output;
    ReadBack read;
};

Generated generate(const RobotCellConfig& cell, int max_lines = 0,
                   std::vector<RobotLayer> layers = two_layers()) {
    Generated g;
    g.layers = std::move(layers);
    g.program = build_print_program(g.layers, cell, {});
    g.output =
        write_rapid_chunks(g.program, cell, {.job_name = "test job", .max_lines = max_lines});
    const std::size_t limit =
        static_cast<std::size_t>(max_lines > 0 ? max_lines : cell.rapid.max_chunk_lines);
    g.read = read_back(g.output, cell, limit);
    return g;
}

}  // namespace

TEST(RapidWriter, ChunksValidateAndAreNamedForTheMainModule) {
    const RobotCellConfig cell;
    const Generated g = generate(cell);
    ASSERT_EQ(g.output.modules.size(), 1u);
    ASSERT_EQ(g.read.modules.size(), 1u);
    const RapidModule& m = g.output.modules[0];
    EXPECT_EQ(m.name, "FcChunk0001");
    EXPECT_EQ(m.file_name, "FcChunk0001.mod");
    const rapid::Module& mod = g.read.modules[0];
    EXPECT_EQ(mod.name, "FcChunk0001");
    ASSERT_EQ(mod.routines.size(), 1u);
    EXPECT_EQ(mod.routines[0].name, "FcChunk0001");
    EXPECT_FALSE(mod.routines[0].local);
    EXPECT_TRUE(mod.routines[0].params.empty());
    // Self-contained LOCAL data: two tools, the bed, speeds and zones.
    for (const rapid::DataDecl& d : mod.data) {
        EXPECT_EQ(d.visibility, rapid::Visibility::local) << d.name;
        EXPECT_LE(d.name.size(), 32u);
    }
    EXPECT_NE(m.text.find("LOCAL PERS tooldata tFcPla"), std::string::npos);
    EXPECT_NE(m.text.find("LOCAL PERS tooldata tFcCcf"), std::string::npos);
    EXPECT_NE(m.text.find("LOCAL PERS wobjdata wFcBed"), std::string::npos);
    for (const unsigned char c : m.text) {
        EXPECT_TRUE(c == '\n' || (c >= 0x20 && c < 0x7f));
    }
    EXPECT_EQ(g.output.stats.moves, g.program.moves.size());
    EXPECT_EQ(g.output.stats.barriers, g.program.stats.barriers);
    EXPECT_EQ(g.output.stats.triggers + g.output.stats.barriers, g.program.events.size());
    EXPECT_EQ(motions(g.read).size(), g.program.moves.size());
}

TEST(RapidWriter, PrintTargetsAreTheToolpathPointsThroughWobjAndTool) {
    const RobotCellConfig cell;
    const Generated g = generate(cell);
    const auto ms = motions(g.read);
    ASSERT_EQ(ms.size(), g.program.moves.size());
    JointVector reference{};
    int checked = 0;
    for (std::size_t i = 0; i < ms.size(); ++i) {
        const ProgramMove& pm = g.program.moves[i];  // only for which toolpath point it is
        const Eigen::Vector3d through_arm = tcp_through_arm(cell, ms[i]->target, reference);
        const Eigen::Vector3d written = ms[i]->target.robtarget->trans_mm;
        EXPECT_NEAR((through_arm - written).norm(), 0, 1e-6);
        if (pm.role != MoveRole::print || pm.point < 0) continue;
        const RobotLayer& layer = g.layers[static_cast<std::size_t>(pm.layer)];
        const Eigen::Vector2d q = layer.paths[static_cast<std::size_t>(pm.path)]
                                      .points[static_cast<std::size_t>(pm.point)];
        const Eigen::Vector3d expected(q.x(), q.y(), layer.z);
        EXPECT_LE((through_arm - expected).norm(), 0.01) << "line " << ms[i]->target.line;
        EXPECT_LE((written - expected).norm(), 0.01);
        ++checked;
    }
    // 4 + 1 PLA moves, 10 + 1 (cut) + 4 + 1 (cut) fibre moves.
    EXPECT_EQ(checked, 4 + 1 + 10 + 4);
}

TEST(RapidWriter, NozzleTiltIsFifteenDegreesForTheActiveNozzle) {
    const RobotCellConfig cell;
    const Generated g = generate(cell);
    int pla = 0, ccf = 0;
    for (const Item* m : motions(g.read)) {
        // The bed's tilt axis: yaw 0 = bed +x.
        const double tilt = signed_tilt_deg(m->target.robtarget->rot, Eigen::Vector3d::UnitX());
        if (m->tool == "tFcPla") {
            EXPECT_NEAR(tilt, 15, 1e-4) << "line " << m->line;
            ++pla;
        } else {
            EXPECT_EQ(m->tool, "tFcCcf");
            EXPECT_NEAR(tilt, -15, 1e-4) << "line " << m->line;
            ++ccf;
        }
        // The idle tip rises: with the tool as read, the other nozzle is 50 sin 15 mm higher.
        const rapid::ToolData& t = *m->target.tool_data;
        const Eigen::Isometry3d tcp =
            to_isometry(m->target.robtarget->trans_mm, m->target.robtarget->rot);
        const Eigen::Isometry3d flange =
            tcp * to_isometry(t.tframe.trans_mm, t.tframe.rot).inverse();
        const NozzleConfig& idle = m->tool == "tFcPla" ? cell.head.ccf : cell.head.pla;
        EXPECT_NEAR((flange * idle.tframe.translation()).z() - tcp.translation().z(),
                    50 * std::sin(15 * pi / 180), 1e-3);
    }
    EXPECT_GT(pla, 5);
    EXPECT_GT(ccf, 15);
}

TEST(RapidWriter, CutLiesTheCutterDistanceBeforeTheFibrePathEnd) {
    const RobotCellConfig cell;
    const Generated g = generate(cell);
    const auto& items = g.read.items;
    int cuts = 0;
    for (const ProgramEvent& e : g.program.events) {
        if (e.kind != EventKind::cut) continue;
        const RobotPath& path =
            g.layers[static_cast<std::size_t>(e.layer)].paths[static_cast<std::size_t>(e.path)];
        long path_end = 0;
        for (const ProgramEvent& f : g.program.events)
            if (f.kind == EventKind::path_end && f.layer == e.layer && f.path == e.path)
                path_end = f.sequence;
        // The trigger that sets the cut's number, the move that carries it, the moves after it
        // up to the one carrying the path end.
        std::size_t k = 0;
        while (k < items.size() &&
               !(items[k].kind == Item::trigger && items[k].value == e.sequence))
            ++k;
        ASSERT_LT(k, items.size());
        EXPECT_TRUE(items[k].lag);
        EXPECT_FALSE(items[k].start);
        const std::string var = items[k].var;
        std::size_t m = k;
        while (m < items.size() && !(items[m].kind == Item::motion &&
                                     std::find(items[m].triggers.begin(), items[m].triggers.end(),
                                               var) != items[m].triggers.end()))
            ++m;
        ASSERT_LT(m, items.size());
        const Eigen::Vector3d cut = items[m].target.robtarget->trans_mm;
        const Eigen::Vector2d expected = before_end(path, 42);
        EXPECT_LE((cut - Eigen::Vector3d(expected.x(), expected.y(), 0.85)).norm(), 0.01);
        double rest = 0;
        Eigen::Vector3d previous = cut;
        bool reached_end = false;
        std::string end_var;
        for (std::size_t i = m + 1; i < items.size() && !reached_end; ++i) {
            if (items[i].kind == Item::trigger && items[i].value == path_end)
                end_var = items[i].var;
            if (items[i].kind != Item::motion) continue;
            const Eigen::Vector3d p = items[i].target.robtarget->trans_mm;
            rest += (p - previous).norm();
            previous = p;
            reached_end = !end_var.empty() &&
                          std::find(items[i].triggers.begin(), items[i].triggers.end(), end_var) !=
                              items[i].triggers.end();
            if (reached_end) {
                EXPECT_EQ(items[i].zone, "fine");
            }
        }
        EXPECT_TRUE(reached_end);
        EXPECT_NEAR(rest, 42, 0.01);
        ++cuts;
    }
    EXPECT_EQ(cuts, 2);
}

TEST(RapidWriter, EventsRunOneToNAcrossChunksAndBarriersFollowStopPoints) {
    const RobotCellConfig cell;
    const Generated g = generate(cell, 45);  // forces many chunks
    ASSERT_GE(g.output.modules.size(), 3u);
    long expected = 1;
    const Item* previous_motion = nullptr;
    for (const Item& i : g.read.items) {
        if (i.kind == Item::motion) {
            previous_motion = &i;
            continue;
        }
        EXPECT_EQ(i.value, expected) << "chunk " << i.chunk + 1 << " line " << i.line;
        expected = i.value + 1;
        if (i.kind == Item::barrier) {
            ASSERT_NE(previous_motion, nullptr);
            EXPECT_EQ(previous_motion->zone, "fine");
        }
    }
    EXPECT_EQ(expected - 1, static_cast<long>(g.program.events.size()));
    // Every trigger is used by the next motion instruction.
    for (std::size_t k = 0; k < g.read.items.size(); ++k) {
        if (g.read.items[k].kind != Item::trigger) continue;
        std::size_t m = k;
        while (g.read.items[m].kind != Item::motion) ++m;
        const auto& t = g.read.items[m].triggers;
        EXPECT_NE(std::find(t.begin(), t.end(), g.read.items[k].var), t.end());
        EXPECT_EQ(g.read.items[m].instruction.substr(0, 5), "Trigg");
    }
}

TEST(RapidWriter, ChunksStayUnderTheLimitAndEndAtTravelStopPoints) {
    const RobotCellConfig cell;
    for (const int limit : {45, 60, 200}) {
        const Generated g = generate(cell, limit);
        std::size_t moves = 0;
        for (std::size_t c = 0; c < g.output.modules.size(); ++c) {
            const RapidModule& m = g.output.modules[c];
            char name[32];
            std::snprintf(name, sizeof name, "FcChunk%04zu", c + 1);
            EXPECT_EQ(m.name, name);
            const auto lines =
                static_cast<std::size_t>(std::count(m.text.begin(), m.text.end(), '\n'));
            EXPECT_LE(lines, static_cast<std::size_t>(limit));
            EXPECT_EQ(lines, m.lines);
            moves += m.end_move - m.first_move;
        }
        EXPECT_EQ(moves, g.program.moves.size());
        // The last motion of each chunk: a stop point at a travel speed.
        for (std::size_t k = 0; k < g.read.items.size(); ++k) {
            const Item& i = g.read.items[k];
            if (i.kind != Item::motion) continue;
            bool last_in_chunk = true;
            for (std::size_t j = k + 1; j < g.read.items.size() && g.read.items[j].chunk == i.chunk;
                 ++j)
                if (g.read.items[j].kind == Item::motion) last_in_chunk = false;
            if (!last_in_chunk) continue;
            EXPECT_EQ(i.zone, "fine") << "chunk " << i.chunk + 1;
            EXPECT_NE(i.speed, "vFcPla");
            EXPECT_NE(i.speed, "vFcCcf");
        }
        if (limit == 45) {
            EXPECT_GE(g.output.modules.size(), 3u);
        }
    }
}

TEST(RapidWriter, HeadSwitchSequenceInTheModules) {
    const RobotCellConfig cell;
    const Generated g = generate(cell);
    const auto& it = g.read.items;
    // The first tFcCcf motion is the turn; before it the PLA lift to head-switch height.
    std::size_t turn = 0;
    while (!(it[turn].kind == Item::motion && it[turn].tool == "tFcCcf")) ++turn;
    std::size_t lift = turn - 1;
    while (it[lift].kind != Item::motion) --lift;
    EXPECT_EQ(it[lift].tool, "tFcPla");
    EXPECT_EQ(it[lift].zone, "fine");
    EXPECT_NEAR(it[lift].target.robtarget->trans_mm.z(), 20.85, 1e-3);
    EXPECT_EQ(it[turn].zone, "fine");
    // Then: barrier, travel, approach (stop), barrier (thread the fibre), the first fibre move.
    ASSERT_LT(turn + 5, it.size());
    EXPECT_EQ(it[turn + 1].kind, Item::barrier);
    EXPECT_EQ(it[turn + 2].kind, Item::motion);
    EXPECT_EQ(it[turn + 2].speed, "vFcTravel");
    EXPECT_EQ(it[turn + 3].kind, Item::motion);
    EXPECT_EQ(it[turn + 3].speed, "vFcApproach");
    EXPECT_EQ(it[turn + 3].zone, "fine");
    EXPECT_EQ(it[turn + 4].kind, Item::barrier);
    EXPECT_EQ(it[turn + 4].value, it[turn + 1].value + 1);
    std::size_t first_print = turn + 5;
    while (it[first_print].kind == Item::trigger) ++first_print;
    EXPECT_EQ(it[first_print].kind, Item::motion);
    EXPECT_EQ(it[first_print].speed, "vFcCcf");
    EXPECT_EQ(it[first_print].tool, "tFcCcf");
}

TEST(RapidWriter, UnreachableTargetNamesThePoint) {
    RobotCellConfig cell;
    cell.bed.translation() = Eigen::Vector3d(700, -150, 100);  // the part 840..860 mm out
    const std::vector<RobotLayer> layers = two_layers();
    const PrintProgram p = build_print_program(layers, cell, {});
    try {
        write_rapid_chunks(p, cell, {});
        FAIL() << "expected an unreachable target";
    } catch (const RapidWriteError& e) {
        const std::string w = e.what();
        EXPECT_NE(w.find("out of reach"), std::string::npos) << w;
        EXPECT_GE(e.layer(), 0);
        EXPECT_NE(w.find("layer " + std::to_string(e.layer() + 1)), std::string::npos) << w;  // said from 1
    }
}

TEST(RapidWriter, AStretchLongerThanAChunkIsAnError) {
    const RobotCellConfig cell;
    RobotLayer l{.index = 0, .z = 0.8, .nozzle = Nozzle::pla};
    RobotPath zig{false, {}};
    for (int i = 0; i < 80; ++i) zig.points.emplace_back(100 + (i % 2) * 20, 100 + i);
    l.paths.push_back(zig);
    const PrintProgram p = build_print_program({l}, cell, {});
    EXPECT_THROW(write_rapid_chunks(p, cell, {.max_lines = 60}), RapidWriteError);
    EXPECT_NO_THROW(write_rapid_chunks(p, cell, {.max_lines = 200}));
}

TEST(RapidWriter, EveryChunkKeepsRoomForItsReentryVersion) {
    // A re-entry rewrites the interrupted chunk in place, with the two lines of the lift: every
    // planned chunk leaves room for them, so the rewritten one fits the same limit.
    const RobotCellConfig cell;
    const int limit = 45;
    const Generated g = generate(cell, limit);
    ASSERT_GE(g.output.modules.size(), 3u);
    for (const RapidModule& m : g.output.modules)
        EXPECT_LE(m.lines, static_cast<std::size_t>(limit - 2)) << m.file_name;
    for (std::size_t c = 1; c < g.output.modules.size(); ++c) {
        const RapidModule& planned = g.output.modules[c];
        const std::size_t from = planned.first_move;
        PrintProgram rest;
        rest.moves.assign(g.program.moves.begin() + static_cast<std::ptrdiff_t>(from),
                          g.program.moves.begin() + static_cast<std::ptrdiff_t>(planned.end_move));
        for (ProgramEvent e : g.program.events)
            if (e.move >= from && e.move < planned.end_move) {
                e.move -= from;
                rest.events.push_back(e);
            }
        const int number = static_cast<int>(c) + 1;
        const RapidOutput again = write_rapid_chunks(
            rest, cell,
            {.max_lines = limit,
             .start_joints = g.output.joints[from - 1],
             .reentry_lift_mm = 5,
             .first_number = number,
             .chunk_count = static_cast<int>(g.output.modules.size())});
        ASSERT_EQ(again.modules.size(), 1u) << planned.file_name;
        EXPECT_EQ(again.modules[0].file_name, planned.file_name);
        EXPECT_LE(again.modules[0].lines, static_cast<std::size_t>(limit));
        EXPECT_NE(again.modules[0].text.find("CRobT"), std::string::npos);
        const rapid::CheckResult check = rapid::check_module(
            again.modules[0].text, validate_options(cell, again.modules[0].file_name, limit));
        for (const auto& d : check.diagnostics) ADD_FAILURE() << rapid::format(d);
        // The same joints from the same reference: the targets' confdata are the planned ones.
        for (std::size_t m = 0; m < rest.moves.size(); ++m)
            EXPECT_EQ(again.joints[m], g.output.joints[from + m]) << "move " << from + m;
    }
}

TEST(RapidWriter, WritesConfLAndTheSignalNamesFromTheConfig) {
    RobotCellConfig cell;
    cell.rapid.confl = true;
    cell.signals.event = "goPrintEvent";
    const Generated g = generate(cell);
    EXPECT_NE(g.output.modules[0].text.find("ConfL \\On;"), std::string::npos);
    EXPECT_NE(g.output.modules[0].text.find("\\GOp:=goPrintEvent, 2;"), std::string::npos);
}

TEST(RapidWriter, ReentryLiftOpensTheFirstChunkOnly) {
    const RobotCellConfig cell;
    const PrintProgram program = build_print_program(two_layers(), cell, {});
    const int limit = 60;
    const RapidOutput out = write_rapid_chunks(program, cell, {.max_lines = limit, .reentry_lift_mm = 5});
    ASSERT_GE(out.modules.size(), 2u);
    // Straight up 5 mm from wherever the robot stands, before the program's first move (a travel
    // with the PLA tool), and nothing else added.
    const std::string& first = out.modules[0].text;
    const std::string lift =
        "    ConfL \\Off;\n"
        "    ! re-entry: straight up from where the robot was held\n"
        "    MoveL Offs(CRobT(\\Tool:=tFcPla \\WObj:=wFcBed),0,0,5), vFcTravel, fine, tFcPla "
        "\\WObj:=wFcBed;\n"
        "    MoveJ [";
    EXPECT_NE(first.find(lift), std::string::npos) << first;
    std::size_t moves = 0;
    for (const RapidModule& m : out.modules) {
        const rapid::CheckResult check =
            rapid::check_module(m.text, validate_options(cell, m.file_name, limit));
        for (const auto& d : check.diagnostics) ADD_FAILURE() << rapid::format(d);
        EXPECT_EQ(m.lines, static_cast<std::size_t>(std::count(m.text.begin(), m.text.end(), '\n')));
        EXPECT_LE(m.lines, static_cast<std::size_t>(limit));
        EXPECT_EQ(m.text.find("CRobT"), &m == &out.modules[0] ? first.find("CRobT") : std::string::npos);
        moves += m.end_move - m.first_move;
    }
    EXPECT_EQ(moves, program.moves.size());
    // Without the option the same program starts at its first move.
    const RapidOutput plain = write_rapid_chunks(program, cell, {.max_lines = limit});
    EXPECT_EQ(plain.modules[0].text.find("CRobT"), std::string::npos);
    EXPECT_THROW(write_rapid_chunks(program, cell, {.reentry_lift_mm = -1}), RapidWriteError);
}
