// The simulated robot's motion on its own thread, in simulated time, on the default IRB 1200
// cell: analytic trapezoids, fly-by junctions and corners, triggers at their positions (and a
// lag earlier), StopMove / StartMove / ClearPath, IK errors, motors off. Targets are print
// targets of the PLA nozzle above the bed, with the confdata of the IK the RAPID writer uses.
#include "drivers/sim/motion/motion_simulator.hpp"

#include "drivers/abb/cell/robot_config.hpp"
#include "drivers/sim/motion/trajectory_analysis.hpp"
#include "tests/support/eventually.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

// Its own namespace: compiled in a batch with the other simulator tests, whose helpers share names.
namespace sim_motion_simulator_test {

using namespace fibrecell::drivers;
using namespace fibrecell::drivers::sim;
using namespace std::chrono_literals;
using fibrecell::test::eventually;

namespace {

constexpr double accel = 1000;  // mm/s^2
constexpr double tick = 0.001;  // s
constexpr double v = 50;        // mm/s
// A trigger fires at the first tick at or after its instant: at most one tick of travel late.
constexpr double trigger_tolerance_mm = v * tick + 1e-6;

const abb::RobotCellConfig cell;  // the simulated cell: bed, dual head, cfx 1

rapid::Pose to_pose(const Eigen::Isometry3d& t) {
    return {.trans_mm = t.translation(), .rot = Eigen::Quaterniond(t.linear())};
}

Eigen::Isometry3d print_pose(const Eigen::Vector3d& bed_mm, double turn_deg = 0) {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear() = (Eigen::AngleAxisd(abb::deg_to_rad(turn_deg), Eigen::Vector3d::UnitZ()) *
                  abb::print_orientation(cell.head, abb::Nozzle::pla))
                     .toRotationMatrix();
    t.translation() = bed_mm;
    return t;
}

// The PLA nozzle at bed point `bed_mm` [mm] (turned about the bed z by `turn_deg`): the
// robtarget with the confdata of its IK solution against `reference`, and the joints.
struct Target {
    rapid::Robtarget robtarget;
    abb::JointVector joints{};
};

Target target_at(const Eigen::Vector3d& bed_mm, const abb::JointVector& reference = {},
                 double turn_deg = 0) {
    const Eigen::Isometry3d pose = print_pose(bed_mm, turn_deg);
    const abb::IkResult ik =
        abb::solve_tcp(cell.model(), cell.frames(abb::Nozzle::pla), pose, reference, cell.solver);
    EXPECT_TRUE(ik.ok()) << ik.failure.reason;
    return {.robtarget = {.trans_mm = bed_mm,
                          .rot = Eigen::Quaterniond(pose.linear()),
                          .conf = {ik.conf.cf1, ik.conf.cf4, ik.conf.cf6, ik.conf.cfx}},
            .joints = ik.joints};
}

MotionSegment move_to(const Target& t, bool fine, const std::string& source,
                      double speed_mm_s = v) {
    MotionSegment s;
    s.target = t.robtarget;
    s.tool.tframe = to_pose(cell.head.pla.tframe);
    s.wobj.uframe = to_pose(cell.bed);
    s.speed = {.v_tcp_mm_s = speed_mm_s, .v_ori_deg_s = 60};
    s.zone = fine ? rapid::ZoneData{.finep = true}
                  : rapid::ZoneData{.pzone_tcp_mm = 0.3, .pzone_ori_mm = 0.45};
    s.source = source;
    return s;
}

// Queues a chain as RAPID's run-ahead would, all before the robot starts: a test thread held
// up between two queue() calls would otherwise let the robot brake for the end of the queue
// (as it should). Returns the ids.
std::vector<std::uint64_t> queue_chain(MotionSimulator& sim, std::vector<MotionSegment> chain) {
    sim.stop_move();
    std::vector<std::uint64_t> ids;
    for (MotionSegment& s : chain) ids.push_back(sim.queue(std::move(s)));
    sim.start_move();
    return ids;
}

// Trigger firings seen from the motion thread: a name and the robot's path position then.
class FiringLog {
  public:
    MotionTrigger trigger(const MotionSimulator& sim, const std::string& name, double distance_mm,
                          bool from_start = false, double lag_s = 0) {
        return {.distance_mm = distance_mm,
                .from_start = from_start,
                .lag_s = lag_s,
                .fire = [this, &sim, name] {
                    const double path = sim.current().path_mm;
                    std::lock_guard lock(mutex_);
                    firings_.push_back({name, path});
                }};
    }
    std::vector<std::pair<std::string, double>> firings() const {
        std::lock_guard lock(mutex_);
        return firings_;
    }
    std::vector<std::string> names() const {
        std::vector<std::string> out;
        for (const auto& f : firings()) out.push_back(f.first);
        return out;
    }
    double path_of(const std::string& name) const {
        for (const auto& f : firings())
            if (f.first == name) return f.second;
        return -1;
    }

  private:
    mutable std::mutex mutex_;
    std::vector<std::pair<std::string, double>> firings_;
};

class MotionSimulatorTest : public ::testing::Test {
  protected:
    // Start above bed point (100, 150, 30); moves go along the bed x axis from there.
    const Eigen::Vector3d start_mm{100, 150, 30};
    const Target home = target_at(start_mm);
    SimClock clock{40};
    // For tests that act while the robot moves: slow enough that a test thread held up by a
    // loaded machine still acts mid-move.
    SimClock slow_clock{10};

    MotionOptions options() const {
        return {.solver = cell.solver,
                .accel_mm_s2 = accel,
                .tick_s = tick,
                .record_period_s = 0.01,
                .start_joints = home.joints};
    }
    Target along_x(double mm) const { return target_at(start_mm + Eigen::Vector3d(mm, 0, 0)); }
};

// Analytic trapezoid from standstill to standstill: path [mm] and speed at time `t` [s].
std::pair<double, double> trapezoid(double length, double t) {
    const double ta = v / accel, da = 0.5 * accel * ta * ta;
    const double total = length / v + ta;
    if (t <= ta) return {0.5 * accel * t * t, accel * t};
    if (t >= total) return {length, 0};
    if (t >= total - ta) {
        const double r = total - t;
        return {length - 0.5 * accel * r * r, accel * r};
    }
    return {da + v * (t - ta), v};
}

// When the robot left its standstill: the first moving sample, back by its analytic time into
// the acceleration (the recording may start with the robot still standing).
double motion_start(const std::vector<TrajectorySample>& trajectory) {
    for (const TrajectorySample& s : trajectory)
        if (s.speed_mm_s > 0) return s.t_s - s.speed_mm_s / accel;
    return trajectory.front().t_s;
}

// The sample of the end of segment `id`.
const TrajectorySample* end_of(const std::vector<TrajectorySample>& trajectory, std::uint64_t id,
                               double path_mm) {
    for (const TrajectorySample& s : trajectory)
        if (s.segment == id && std::abs(s.path_mm - path_mm) < 1e-9) return &s;
    return nullptr;
}

}  // namespace

TEST_F(MotionSimulatorTest, FineMoveFollowsTheAnalyticTrapezoid) {
    MotionSimulator sim(clock, options());
    const Target end = along_x(100);
    const std::uint64_t id = sim.queue(move_to(end, true, "FcChunk0001 line 12"));
    EXPECT_EQ(id, 1u);
    ASSERT_TRUE(eventually([&] { return sim.in_position(); }));
    EXPECT_TRUE(sim.done(id));
    EXPECT_EQ(sim.status().last_done, id);
    EXPECT_EQ(sim.status().pending, 0u);

    const std::vector<TrajectorySample> trajectory = sim.take_trajectory();
    ASSERT_GT(trajectory.size(), 200u);  // one per 10 ms over 2.05 s, plus start and end
    const double t0 = trajectory.front().t_s;
    EXPECT_EQ(trajectory.front().path_mm, 0);
    EXPECT_EQ(trajectory.front().speed_mm_s, 0);
    // 0.05 s to accelerate over 1.25 mm, 97.5 mm at 50 mm/s, 0.05 s to brake.
    EXPECT_NEAR(trajectory.back().t_s - t0, 100 / v + v / accel, 2 * tick);
    EXPECT_NEAR(trajectory.back().path_mm, 100, 1e-9);
    for (const TrajectorySample& s : trajectory) {
        const auto [path, speed] = trapezoid(100, s.t_s - t0);
        ASSERT_NEAR(s.path_mm, path, 1e-6) << "at " << s.t_s - t0 << " s";
        ASSERT_NEAR(s.speed_mm_s, speed, 1e-6) << "at " << s.t_s - t0 << " s";
        ASSERT_NEAR((s.tcp_wobj_mm - (start_mm + Eigen::Vector3d(path, 0, 0))).norm(), 0, 1e-6);
        ASSERT_NEAR((s.tcp_base_mm - cell.bed * s.tcp_wobj_mm).norm(), 0, 1e-9);
        EXPECT_EQ(s.source, "FcChunk0001 line 12");
    }
    const TrajectorySample now = sim.current();
    EXPECT_NEAR(now.path_mm, 100, 1e-9);
    EXPECT_EQ(now.speed_mm_s, 0);
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(now.joints[i], end.joints[i], 1e-9);
}

TEST_F(MotionSimulatorTest, ShortMoveIsATriangle) {
    MotionSimulator sim(clock, options());
    // 2 mm < v^2/a = 2.5 mm: the peak is sqrt(a L) < v, halfway in time.
    sim.queue(move_to(along_x(2), true, "short"));
    ASSERT_TRUE(eventually([&] { return sim.in_position(); }));
    const auto trajectory = sim.take_trajectory();
    const double t0 = trajectory.front().t_s, half = std::sqrt(2 / accel);
    EXPECT_NEAR(trajectory.back().t_s - t0, 2 * half, 2 * tick);
    const auto peak = sample_at(trajectory, clock.wall_at(t0 + half));
    ASSERT_TRUE(peak);
    EXPECT_NEAR(peak->path_mm, 1, 0.02);  // linear between samples 10 ms apart
    double fastest = 0;
    for (const auto& s : trajectory) fastest = std::max(fastest, s.speed_mm_s);
    EXPECT_LE(fastest, std::sqrt(accel * 2) + 1e-9);
    EXPECT_GT(fastest, std::sqrt(accel * 2) - accel * 0.01);
}

TEST_F(MotionSimulatorTest, CollinearFlyByKeepsTheSpeed) {
    MotionSimulator sim(clock, options());
    queue_chain(sim, {move_to(along_x(30), false, "a"), move_to(along_x(60), false, "b"),
                      move_to(along_x(90), true, "c")});
    ASSERT_TRUE(eventually([&] { return sim.in_position(); }));
    const auto trajectory = sim.take_trajectory();
    const double t0 = motion_start(trajectory);
    EXPECT_NEAR(trajectory.back().t_s - t0, 90 / v + v / accel, 2 * tick);
    ASSERT_TRUE(end_of(trajectory, 1, 30));
    ASSERT_TRUE(end_of(trajectory, 2, 60));
    EXPECT_NEAR(end_of(trajectory, 1, 30)->speed_mm_s, v, 1e-9);
    EXPECT_NEAR(end_of(trajectory, 2, 60)->speed_mm_s, v, 1e-9);
    for (const auto& s : trajectory) {
        if (s.path_mm > 1.25 + 1e-6 && s.path_mm < 90 - 1.25 - 1e-6) {
            ASSERT_NEAR(s.speed_mm_s, v, 1e-9) << "dip at " << s.path_mm << " mm";
        }
    }
}

TEST_F(MotionSimulatorTest, SquareCornerStopsAndAnObliqueOneSlows) {
    MotionSimulator sim(clock, options());
    // 90 deg at the first corner, then 45 deg: min(v_in, v_out) * (90 - 45) / 85.
    queue_chain(sim, {move_to(along_x(40), false, "x"),
                      move_to(target_at(start_mm + Eigen::Vector3d(40, -40, 0)), false, "square"),
                      move_to(target_at(start_mm + Eigen::Vector3d(80, -80, 0)), true, "oblique")});
    ASSERT_TRUE(eventually([&] { return sim.in_position(); }));
    const auto trajectory = sim.take_trajectory();
    const TrajectorySample* corner = end_of(trajectory, 1, 40);
    const TrajectorySample* oblique = end_of(trajectory, 2, 80);
    ASSERT_TRUE(corner && oblique);
    EXPECT_EQ(corner->speed_mm_s, 0);
    EXPECT_NEAR(oblique->speed_mm_s, v * 45 / 85, 1e-9);
    EXPECT_NEAR(trajectory.back().path_mm, 80 + 40 * std::sqrt(2), 1e-9);
}

TEST_F(MotionSimulatorTest, TriggersFireOnceAtTheirPositions) {
    FiringLog log;  // outlives the simulator that calls it
    MotionSimulator sim(clock, options());
    MotionSegment first = move_to(along_x(100), false, "first");
    first.triggers = {log.trigger(sim, "end", 0), log.trigger(sim, "start", 0, true),
                      log.trigger(sim, "40 before the end", 40),
                      log.trigger(sim, "10 after the start", 10, true)};
    MotionSegment second = move_to(along_x(160), true, "second");
    // 20 mm before the end with a 0.05 s lag: at 140 - v * 0.05 = 137.5 mm.
    second.triggers = {log.trigger(sim, "stop point", 0),
                       log.trigger(sim, "lagged", 20, false, 0.05)};
    queue_chain(sim, {std::move(first), std::move(second)});
    ASSERT_TRUE(eventually([&] { return sim.in_position(); }));

    EXPECT_EQ(log.names(),
              (std::vector<std::string>{"start", "10 after the start", "40 before the end", "end",
                                        "lagged", "stop point"}));
    const std::vector<std::pair<std::string, double>> expected{
        {"start", 0}, {"10 after the start", 10}, {"40 before the end", 60},
        {"end", 100}, {"lagged", 137.5},          {"stop point", 160}};
    for (const auto& [name, at] : expected) {
        EXPECT_GE(log.path_of(name), at - 1e-6) << name;
        EXPECT_LE(log.path_of(name), at + trigger_tolerance_mm) << name;
    }
}

TEST_F(MotionSimulatorTest, StopMoveBrakesOnThePathAndStartMoveCompletesIt) {
    FiringLog log;  // outlives the simulator that calls it
    MotionSimulator sim(slow_clock, options());
    MotionSegment move = move_to(along_x(150), true, "long");
    move.triggers = {log.trigger(sim, "end", 0)};
    sim.queue(std::move(move));
    ASSERT_TRUE(eventually([&] { return sim.current().path_mm >= 40; }));
    sim.stop_move();
    ASSERT_TRUE(eventually([&] { return !sim.status().moving; }));
    const TrajectorySample stopped = sim.current();
    EXPECT_TRUE(sim.status().stopped);
    EXPECT_EQ(sim.status().pending, 1u);
    EXPECT_FALSE(sim.in_position());
    EXPECT_EQ(stopped.speed_mm_s, 0);
    EXPECT_LT(stopped.path_mm, 150 - 1.25);
    EXPECT_NEAR((stopped.tcp_wobj_mm - (start_mm + Eigen::Vector3d(stopped.path_mm, 0, 0))).norm(),
                0, 1e-6);
    // 0.4 s of the simulator's own time later, it has stayed put.
    ASSERT_TRUE(eventually([&] { return slow_clock.now_s() >= stopped.t_s + 0.4; }));
    EXPECT_EQ(sim.current().path_mm, stopped.path_mm);
    EXPECT_TRUE(log.firings().empty());

    // Braked at `accel` from full speed: every sample taken while braking (every 0.01 s, so at
    // least four in the 0.05 s it takes) lies on the analytic ramp down to the standstill, at
    // speed s with s^2 / (2 accel) left to go. The standstill sample itself is taken at the
    // motion thread's next tick, so its time is not the analytic one.
    const auto braking = sim.take_trajectory();
    EXPECT_EQ(braking.back().path_mm, stopped.path_mm);
    auto last_full = std::find_if(braking.rbegin(), braking.rend(), [](const auto& s) {
        return s.speed_mm_s >= v - 1e-9;
    });
    ASSERT_NE(last_full, braking.rend());
    std::vector<TrajectorySample> ramp;
    for (auto it = last_full.base(); it != braking.end(); ++it)
        if (it->speed_mm_s > 0) ramp.push_back(*it);
    ASSERT_GE(ramp.size(), 4u);
    for (std::size_t i = 0; i < ramp.size(); ++i) {
        const double s = ramp[i].speed_mm_s;
        EXPECT_NEAR(stopped.path_mm - ramp[i].path_mm, s * s / (2 * accel), 1e-9) << i;
        if (i > 0) {
            EXPECT_NEAR(ramp[i - 1].speed_mm_s - s, accel * (ramp[i].t_s - ramp[i - 1].t_s), 1e-6)
                << i;
        }
    }

    sim.start_move();
    ASSERT_TRUE(eventually([&] { return sim.in_position(); }));
    EXPECT_NEAR(sim.current().path_mm, 150, 1e-9);
    EXPECT_NEAR((sim.current().tcp_wobj_mm - (start_mm + Eigen::Vector3d(150, 0, 0))).norm(), 0,
                1e-9);
    ASSERT_EQ(log.names(), std::vector<std::string>{"end"});
    // Nothing skipped or repeated: the path grows by the distance moved, on the line.
    const auto rest = sim.take_trajectory();
    EXPECT_EQ(rest.front().path_mm, stopped.path_mm);
    for (std::size_t i = 1; i < rest.size(); ++i) {
        const double step = rest[i].path_mm - rest[i - 1].path_mm;
        ASSERT_GE(step, 0);
        ASSERT_NEAR((rest[i].tcp_wobj_mm - rest[i - 1].tcp_wobj_mm).norm(), step, 1e-9);
    }
}

TEST_F(MotionSimulatorTest, ClearPathDropsTheRestAndItsTriggers) {
    FiringLog log;  // outlives the simulator that calls it
    MotionSimulator sim(slow_clock, options());
    MotionSegment first = move_to(along_x(100), false, "first");
    first.triggers = {log.trigger(sim, "first end", 0)};
    MotionSegment second = move_to(along_x(160), true, "second");
    second.triggers = {log.trigger(sim, "second start", 0, true)};
    const auto ids = queue_chain(sim, {std::move(first), std::move(second)});
    ASSERT_TRUE(eventually([&] { return sim.current().path_mm >= 30; }));
    sim.clear_path();  // while moving: it stops first
    EXPECT_TRUE(sim.status().stopped);
    EXPECT_EQ(sim.status().pending, 0u);
    EXPECT_TRUE(sim.done(ids[0]) && sim.done(ids[1]));
    ASSERT_TRUE(eventually([&] { return sim.in_position(); }));
    const TrajectorySample stopped = sim.current();
    EXPECT_LT(stopped.path_mm, 100 - 1.25);
    EXPECT_EQ(sim.status().last_done, 0u);

    // The next move starts where the robot stands.
    const Eigen::Vector3d side = start_mm + Eigen::Vector3d(50, 30, 0);
    const auto id3 = sim.queue(move_to(target_at(side, home.joints), true, "after"));
    EXPECT_EQ(id3, 3u);
    sim.start_move();
    ASSERT_TRUE(eventually([&] { return sim.in_position(); }));
    sim.start_move();  // nothing to resume; as every command, waits for the last tick's triggers
    EXPECT_TRUE(log.firings().empty());
    EXPECT_EQ(sim.status().last_done, id3);
    EXPECT_NEAR((sim.current().tcp_wobj_mm - side).norm(), 0, 1e-9);
    EXPECT_NEAR(sim.current().path_mm, stopped.path_mm + (side - stopped.tcp_wobj_mm).norm(), 1e-9);
}

TEST_F(MotionSimulatorTest, UnreachableTargetOrWrongConfigurationIsAControllerError) {
    MotionSimulator sim(clock, options());
    Target far = along_x(100);
    far.robtarget.trans_mm.z() = 900;  // 1000 mm above the base plate
    try {
        sim.queue(move_to(far, true, "FcChunk0001 line 7"));
        ADD_FAILURE() << "queued an unreachable target";
    } catch (const MotionError& e) {
        EXPECT_NE(std::string(e.what()).find("FcChunk0001 line 7: target unreachable on cfx 1: "
                                             "out of reach"),
                  std::string::npos)
            << e.what();
    }
    Target flipped = along_x(100);
    flipped.robtarget.conf.cfx = 0;  // wrist flipped: not where a straight line from cfx 1 ends
    try {
        sim.queue(move_to(flipped, true, "FcChunk0001 line 8"));
        ADD_FAILURE() << "queued a linear move that changes the arm configuration";
    } catch (const MotionError& e) {
        EXPECT_NE(std::string(e.what()).find("FcChunk0001 line 8: "), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("cfx"), std::string::npos) << e.what();
    }
    MotionSegment joint_move = move_to(flipped, true, "FcChunk0001 line 9");
    joint_move.joint = true;
    EXPECT_THROW(sim.queue(joint_move), MotionError);
    Target quadrant = along_x(100);
    quadrant.robtarget.conf.cf6 += 1;
    MotionSegment wrong_cf6 = move_to(quadrant, true, "FcChunk0001 line 10");
    wrong_cf6.joint = true;
    try {
        sim.queue(wrong_cf6);
        ADD_FAILURE() << "queued a joint move whose axis-6 quadrant differs";
    } catch (const MotionError& e) {
        EXPECT_NE(std::string(e.what()).find("FcChunk0001 line 10: the solution's confdata"),
                  std::string::npos)
            << e.what();
    }

    EXPECT_EQ(sim.status().pending, 0u);
    EXPECT_TRUE(sim.in_position());
    EXPECT_EQ(sim.queue(move_to(along_x(10), true, "good")), 1u);  // nothing was queued
    ASSERT_TRUE(eventually([&] { return sim.in_position(); }));
    EXPECT_NEAR(sim.current().path_mm, 10, 1e-9);
}

TEST_F(MotionSimulatorTest, MotorsOffHoldsTheRobotUntilMotorsOn) {
    FiringLog log;  // outlives the simulator that calls it
    MotionSimulator sim(slow_clock, options());
    MotionSegment move = move_to(along_x(150), true, "long");
    move.triggers = {log.trigger(sim, "end", 0)};
    sim.queue(std::move(move));
    ASSERT_TRUE(eventually([&] { return sim.current().path_mm >= 20; }));
    sim.motors_off("emergency stop");
    const MotionStatus off = sim.status();
    EXPECT_FALSE(off.motors_on);
    EXPECT_FALSE(off.moving);
    EXPECT_EQ(off.pending, 0u);
    EXPECT_EQ(off.error, "emergency stop");
    const TrajectorySample held = sim.current();
    EXPECT_EQ(held.speed_mm_s, 0);
    ASSERT_TRUE(eventually([&] { return slow_clock.now_s() >= held.t_s + 0.4; }));
    EXPECT_EQ(sim.current().path_mm, held.path_mm);
    try {
        sim.queue(move_to(along_x(50), true, "FcChunk0002 line 3"));
        ADD_FAILURE() << "queued with the motors off";
    } catch (const MotionError& e) {
        EXPECT_NE(std::string(e.what()).find("FcChunk0002 line 3: motors off (emergency stop)"),
                  std::string::npos)
            << e.what();
    }

    sim.motors_on();
    EXPECT_TRUE(sim.status().motors_on);
    EXPECT_EQ(sim.status().error, "");
    sim.queue(move_to(along_x(50), true, "back"));
    ASSERT_TRUE(eventually([&] { return sim.in_position(); }));
    EXPECT_NEAR(sim.current().path_mm, held.path_mm + std::abs(held.path_mm - 50), 1e-9);
    EXPECT_TRUE(log.firings().empty());
}

TEST_F(MotionSimulatorTest, ReorientationTakesTurnOverVori) {
    MotionSimulator sim(clock, options());
    // 30 deg about the bed z at 60 deg/s: 0.5 s in place; then 10 mm turning back the 30 deg,
    // which v_ori paces at 10 mm / 0.5 s = 20 mm/s.
    const auto turn = queue_chain(sim, {move_to(target_at(start_mm, home.joints, 30), true, "turn"),
                                        move_to(along_x(10), true, "turn back")})[0];
    ASSERT_TRUE(eventually([&] { return sim.in_position(); }));
    const auto trajectory = sim.take_trajectory();
    const double t0 = trajectory.front().t_s;
    // The last sample on the turn is its end.
    const auto turned = std::find_if(trajectory.rbegin(), trajectory.rend(),
                                     [&](const TrajectorySample& s) { return s.segment == turn; });
    ASSERT_NE(turned, trajectory.rend());
    EXPECT_NEAR(turned->t_s - t0, 0.5, 1e-9);
    double fastest = 0;
    for (const auto& s : trajectory) fastest = std::max(fastest, s.speed_mm_s);
    EXPECT_NEAR(fastest, 20, 1e-9);
    EXPECT_NEAR(trajectory.back().path_mm, 10, 1e-9);
}

TEST_F(MotionSimulatorTest, LinearMoveFromTheAllZeroStartJointsIsAccepted) {
    // J5 = 0 is the wrist singularity, where both wrist branches meet: a MoveL onto cfx 1 is fine.
    MotionSimulator sim(clock, {.solver = cell.solver, .accel_mm_s2 = accel});
    const TrajectorySample home_pose = sim.current();
    EXPECT_NEAR((home_pose.tcp_base_mm - Eigen::Vector3d(433, 0, 791.1)).norm(), 0, 1e-9);
    sim.queue(move_to(along_x(0), true, "FcChunk0001 line 5", 500));
    ASSERT_TRUE(eventually([&] { return sim.in_position(); }));
    EXPECT_NEAR((sim.current().tcp_wobj_mm - start_mm).norm(), 0, 1e-9);
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(sim.current().joints[i], home.joints[i], 1e-9);
}

TEST_F(MotionSimulatorTest, CatchingUpWithAFastClockStillFiresTriggersInPlace) {
    // At 1000x a 1 ms tick is 1 us of real time, less than one pass of the motion thread: it
    // falls behind and catches up in steps larger than a tick, stopping at each trigger so that
    // the trigger still sees the robot at its position. (How well it keeps pace is a figure of
    // sync_bench, not asserted here; the elapsed ratio is recorded.)
    SimClock fast{1000};
    FiringLog log;
    MotionSimulator sim(fast, options());
    MotionSegment line = move_to(along_x(160), true, "long line");
    line.triggers = {log.trigger(sim, "at 40", 40, true), log.trigger(sim, "at 120", 120, true)};
    sim.queue(std::move(line));
    ASSERT_TRUE(eventually([&] { return sim.in_position(); }));
    const double seen_s = fast.now_s();
    const auto trajectory = sim.take_trajectory();
    ASSERT_FALSE(trajectory.empty());
    EXPECT_NEAR(trajectory.back().path_mm, 160, 1e-9);
    // How far behind the clock the robot finished (simulated s), as seen by this thread.
    RecordProperty("finish_lag_s", std::to_string(seen_s - trajectory.back().t_s));
    EXPECT_NEAR(sim.current().path_mm, 160, 1e-9);
    EXPECT_GE(log.path_of("at 40"), 40 - 1e-6);
    EXPECT_LE(log.path_of("at 40"), 40 + trigger_tolerance_mm);
    EXPECT_GE(log.path_of("at 120"), 120 - 1e-6);
    EXPECT_LE(log.path_of("at 120"), 120 + trigger_tolerance_mm);
}

}  // namespace sim_motion_simulator_test
