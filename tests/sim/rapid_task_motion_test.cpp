// Motion and loading in the simulated RAPID task: MoveL/TriggL queue segments on the
// MotionSimulator, a stop point holds the program until the robot stands there, TriggIO outputs
// are written through TaskIo at their path positions, an unreachable target is an error at its
// line; StartLoad/WaitLoad link a module read through TaskIo.read_file (validated against the I/O
// configuration) and UnLoad removes it.
#include "drivers/sim/rapid_exec/rapid_task.hpp"

#include "drivers/abb/cell/robot_config.hpp"
#include "drivers/abb/kinematics/confdata.hpp"
#include "drivers/abb/kinematics/joint_solver.hpp"
#include "drivers/abb/kinematics/opw_kinematics.hpp"
#include "drivers/abb/rapid/reader.hpp"
#include "tests/support/eventually.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

// Its own namespace: compiled in a batch with the other simulator tests, whose helpers share names.
namespace sim_rapid_task_motion_test {

using namespace fibrecell::drivers;
using namespace fibrecell::drivers::sim;
using namespace std::chrono_literals;
using fibrecell::test::eventually;

namespace {

const abb::RobotCellConfig cell;
constexpr double v = 50;        // mm/s
constexpr double tick = 0.001;  // s, the motion thread's step
const std::vector<std::string> signals = {"goCode", "doLamp"};

std::string number(double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9f", x);
    return buf;
}

std::string pose_text(const Eigen::Vector3d& t, const Eigen::Quaterniond& q) {
    return "[[" + number(t.x()) + "," + number(t.y()) + "," + number(t.z()) + "],[" +
           number(q.w()) + "," + number(q.x()) + "," + number(q.y()) + "," + number(q.z()) + "]]";
}

// The PLA nozzle at bed point `bed_mm`, as a RAPID robtarget literal with the IK's confdata.
struct Target {
    std::string text;
    abb::JointVector joints{};
};

Target target_at(const Eigen::Vector3d& bed_mm) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = abb::print_orientation(cell.head, abb::Nozzle::pla).toRotationMatrix();
    pose.translation() = bed_mm;
    const abb::IkResult ik =
        abb::solve_tcp(cell.model(), cell.frames(abb::Nozzle::pla), pose, {}, cell.solver);
    EXPECT_TRUE(ik.ok()) << ik.failure.reason;
    const Eigen::Quaterniond q(pose.linear());
    return {.text = "[" + pose_text(bed_mm, q).substr(1, pose_text(bed_mm, q).size() - 2) +
                    ",[" + std::to_string(ik.conf.cf1) + "," + std::to_string(ik.conf.cf4) + "," +
                    std::to_string(ik.conf.cf6) + "," + std::to_string(ik.conf.cfx) +
                    "],[9E9,9E9,9E9,9E9,9E9,9E9]]",
            .joints = ik.joints};
}

// Tool, work object and speed declarations of the default cell.
std::string cell_data() {
    const Eigen::Isometry3d& tool = cell.head.pla.tframe;
    return "  PERS tooldata tPla := [TRUE," +
           pose_text(tool.translation(), Eigen::Quaterniond(tool.linear())) +
           ",[0.5,[0,0,20],[1,0,0,0],0,0,0]];\n"
           "  PERS wobjdata wBed := [FALSE,TRUE,\"\"," +
           pose_text(cell.bed.translation(), Eigen::Quaterniond(cell.bed.linear())) +
           ",[[0,0,0],[1,0,0,0]]];\n"
           "  CONST speeddata vPrint := [50,60,5000,1000];\n";
}

class RapidTaskMotion : public ::testing::Test {
  protected:
    const Eigen::Vector3d start_mm{100, 150, 30};
    const Target home = target_at(start_mm);
    SimClock clock{20};
    MotionSimulator motion{clock, {.solver = cell.solver,
                                   .accel_mm_s2 = 1000,
                                   .tick_s = tick,
                                   .start_joints = home.joints}};
    std::mutex mu;
    std::map<std::string, double> values{{"goCode", 0}, {"doLamp", 0}};
    std::map<std::string, std::string> files;
    // Each output write with the robot's path position and TCP (work object) at that moment.
    struct Write {
        std::string signal;
        double value;
        double path_mm;
        Eigen::Vector3d tcp_mm;
    };
    std::vector<Write> writes;
    RapidTask task{clock, motion, io()};

    TaskIo io() {
        return {.read_signal =
                    [this](const std::string& s) {
                        const std::lock_guard g(mu);
                        return values.at(s);
                    },
                .write_signal =
                    [this](const std::string& s, double x) {
                        const TrajectorySample now = motion.current();
                        const std::lock_guard g(mu);
                        values.at(s) = x;
                        writes.push_back({s, x, now.path_mm, now.tcp_wobj_mm});
                    },
                .read_file =
                    [this](const std::string& path) -> std::optional<std::string> {
                        const std::lock_guard g(mu);
                        auto it = files.find(path);
                        if (it == files.end()) return std::nullopt;
                        return it->second;
                    },
                .log = {},
                .known_signals = signals};
    }
    abb::rapid::Module module_of(const std::string& text) {
        abb::rapid::ValidateOptions o;
        o.known_signals = signals;
        return abb::rapid::read_module(text, o);
    }
    TaskStatus run(const std::string& text) {
        task.load(module_of(text));
        task.reset_pp();
        task.start();
        EXPECT_TRUE(eventually([&] { return task.status().state != TaskState::running; }));
        return task.status();
    }
    std::vector<Write> taken() {
        const std::lock_guard g(mu);
        return writes;
    }
};

}  // namespace

TEST_F(RapidTaskMotion, MovesReachTheirTargetsAndTriggersFireAtTheirPositions) {
    const Target end = target_at(start_mm + Eigen::Vector3d(40, 0, 0));
    const TaskStatus s = run("MODULE M\n" + cell_data() +
                             "  CONST robtarget pHome := " + home.text + ";\n"
                             "  CONST robtarget pEnd := " + end.text + ";\n"
                             "  PERS num nAtEnd := 0;\n"
                             "  PROC main()\n"
                             "    VAR triggdata tgA;\n"
                             "    VAR triggdata tgB;\n"
                             "    MoveL pHome, vPrint, fine, tPla \\WObj:=wBed;\n"
                             "    TriggIO tgA, 10 \\Start \\GOp:=goCode, 5;\n"
                             "    TriggIO tgB, 0 \\GOp:=goCode, 6;\n"
                             "    TriggL pEnd, vPrint, tgA \\T2:=tgB, fine, tPla \\WObj:=wBed;\n"
                             "    SetDO doLamp, 1;\n"
                             "    MoveL Offs(pEnd, 0, 0, 5), vPrint, fine, tPla \\WObj:=wBed;\n"
                             "  ENDPROC\n"
                             "ENDMODULE\n");
    ASSERT_EQ(s.state, TaskState::stopped) << s.error;
    const auto w = taken();
    ASSERT_EQ(w.size(), 3u);
    // \Start 10: 10 mm into the 40 mm line; 0 without \Start: at its end. At most one tick late.
    EXPECT_EQ(w[0].signal, "goCode");
    EXPECT_EQ(w[0].value, 5);
    EXPECT_NEAR(w[0].path_mm, 10, v * tick + 1e-6);
    EXPECT_NEAR(w[0].tcp_mm.x(), start_mm.x() + 10, v * tick + 1e-6);
    EXPECT_EQ(w[1].value, 6);
    EXPECT_NEAR(w[1].path_mm, 40, 1e-6);
    // The stop point holds the program: SetDO comes with the robot standing at pEnd.
    EXPECT_EQ(w[2].signal, "doLamp");
    EXPECT_NEAR(w[2].path_mm, 40, 1e-6);
    EXPECT_TRUE(w[2].tcp_mm.isApprox(start_mm + Eigen::Vector3d(40, 0, 0), 1e-6));
    // The last move (queued after the SetDO) ended 5 mm above pEnd.
    EXPECT_TRUE(motion.current().tcp_wobj_mm.isApprox(start_mm + Eigen::Vector3d(40, 0, 5), 1e-6));
    EXPECT_NEAR(motion.current().path_mm, 45, 1e-6);
}

TEST_F(RapidTaskMotion, UnreachableTargetIsAnErrorAtItsLine) {
    const TaskStatus s = run("MODULE M\n" + cell_data() +
                             "  CONST robtarget pHome := " + home.text + ";\n"
                             "  PROC main()\n"
                             "    MoveL pHome, vPrint, fine, tPla \\WObj:=wBed;\n"
                             "    MoveL Offs(pHome, 3000, 0, 0), vPrint, fine, tPla \\WObj:=wBed;\n"
                             "  ENDPROC\n"
                             "ENDMODULE\n");
    EXPECT_EQ(s.state, TaskState::error);
    EXPECT_EQ(s.error.rfind("M line 8: target unreachable", 0), 0u) << s.error;
}

TEST_F(RapidTaskMotion, CRobTIsWhereTheRobotStandsAndOffsOfItLiftsStraightUp) {
    const Eigen::Vector3d side_mm = start_mm + Eigen::Vector3d(30, 20, 0);
    const Target side = target_at(side_mm);
    const std::string unset = "[[0,0,0],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]]";
    const TaskStatus s = run("MODULE M\n" + cell_data() +
                             "  CONST robtarget pHome := " + home.text + ";\n"
                             "  CONST robtarget pSide := " + side.text + ";\n"
                             "  PERS robtarget pNow := " + unset + ";\n"
                             "  PERS robtarget pFlange := " + unset + ";\n"
                             "  PROC main()\n"
                             "    MoveL pHome, vPrint, fine, tPla \\WObj:=wBed;\n"
                             "    MoveL pSide, vPrint, fine, tPla \\WObj:=wBed;\n"
                             "    pNow := CRobT(\\Tool:=tPla \\WObj:=wBed);\n"
                             "    pFlange := CRobT();\n"
                             "    MoveL Offs(CRobT(\\Tool:=tPla \\WObj:=wBed), 0, 0, 5), vPrint, "
                             "fine, tPla \\WObj:=wBed;\n"
                             "  ENDPROC\n"
                             "ENDMODULE\n");
    ASSERT_EQ(s.state, TaskState::stopped) << s.error;

    // The PLA TCP in the bed frame where the robot stood, with the IK's confdata.
    const auto now = abb::rapid::to_robtarget(task.read_data("M", "pNow"));
    ASSERT_TRUE(now);
    EXPECT_LT((now->trans_mm - side_mm).norm(), 1e-6);
    const Eigen::Quaterniond print_rot(abb::print_orientation(cell.head, abb::Nozzle::pla));
    EXPECT_NEAR(std::abs(now->rot.dot(print_rot)), 1, 1e-9);
    const auto want = abb::confdata(cell.model().geometry, side.joints);
    EXPECT_EQ(now->conf.cf1, want.cf1);
    EXPECT_EQ(now->conf.cf4, want.cf4);
    EXPECT_EQ(now->conf.cf6, want.cf6);
    EXPECT_EQ(now->conf.cfx, want.cfx);
    // No \Tool, no \WObj: tool0 in wobj0, the flange in the base frame.
    const auto flange = abb::rapid::to_robtarget(task.read_data("M", "pFlange"));
    ASSERT_TRUE(flange);
    const Eigen::Isometry3d fk = abb::forward_kinematics(cell.model().geometry, side.joints);
    EXPECT_LT((flange->trans_mm - fk.translation()).norm(), 1e-6);

    // The lift: 5 mm straight up from there, orientation kept.
    const auto trajectory = motion.take_trajectory();
    std::size_t lift_samples = 0;
    for (const TrajectorySample& t : trajectory) {
        if (t.segment != 3) continue;
        ++lift_samples;
        EXPECT_NEAR(t.tcp_wobj_mm.x(), side_mm.x(), 1e-6);
        EXPECT_NEAR(t.tcp_wobj_mm.y(), side_mm.y(), 1e-6);
        EXPECT_GE(t.tcp_wobj_mm.z(), side_mm.z() - 1e-6);
    }
    EXPECT_GT(lift_samples, 5u);
    EXPECT_LT((motion.current().tcp_wobj_mm - (side_mm + Eigen::Vector3d(0, 0, 5))).norm(), 1e-6);
}

TEST_F(RapidTaskMotion, StartLoadWaitLoadLateCallAndUnLoad) {
    const std::string main_text = R"(MODULE Main
  PERS num nLoaded := 0;
  PERS string sPath := "HOME:/job/Part1.mod";
  VAR loadsession ls;
  VAR string sName := "Part1";
  PROC main()
    StartLoad \Dynamic, sPath, ls;
    WaitLoad ls;
    %sName%;
    nLoaded := nLoaded + 1;
    UnLoad sPath;
    nLoaded := nLoaded + 10;
  ENDPROC
  PROC Count(num n)
    nLoaded := nLoaded + n;
  ENDPROC
ENDMODULE
)";
    files["HOME:/job/Part1.mod"] = R"(MODULE Part1
  PROC Part1()
    SetDO doLamp, 1;
    Count 100;
  ENDPROC
ENDMODULE
)";
    abb::rapid::ValidateOptions o;
    o.known_signals = signals;
    task.load(abb::rapid::read_module(main_text, o));
    task.reset_pp();
    task.start();
    ASSERT_TRUE(eventually([&] { return task.status().state != TaskState::running; }));
    ASSERT_EQ(task.status().state, TaskState::stopped) << task.status().error;
    EXPECT_EQ(task.read_data("Main", "nLoaded").num(), 111);
    EXPECT_EQ(task.status().loaded, std::vector<std::string>{"Main"});  // Part1 unloaded
    EXPECT_EQ(values.at("doLamp"), 1);

    // A module that does not link (a signal outside the I/O configuration): the error names
    // the instruction's line and the file's.
    files["HOME:/job/Part1.mod"] =
        "MODULE Part1\n  PROC Part1()\n    SetDO doOther, 1;\n  ENDPROC\nENDMODULE\n";
    task.reset_pp();
    task.start();
    ASSERT_TRUE(eventually([&] { return task.status().state != TaskState::running; }));
    EXPECT_EQ(task.status().state, TaskState::error);
    EXPECT_EQ(task.status().error.rfind("Main line 8: WaitLoad: HOME:/job/Part1.mod does not link: "
                                        "Part1.mod:3",
                                        0),
              0u)
        << task.status().error;

    // A missing file fails at StartLoad.
    task.write_data("Main", "sPath", abb::rapid::string_value("HOME:/job/Part9.mod"));
    task.reset_pp();
    task.start();
    ASSERT_TRUE(eventually([&] { return task.status().state != TaskState::running; }));
    EXPECT_EQ(task.status().error,
              "Main line 7: StartLoad: no file HOME:/job/Part9.mod (ERR_FILNOTFND)");
    EXPECT_EQ(task.status().loaded, std::vector<std::string>{"Main"});
}

}  // namespace sim_rapid_task_motion_test
