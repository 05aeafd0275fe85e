// Reading a recorded trajectory back at a steady-clock instant: between samples, on a sample,
// outside the recording.
#include "drivers/sim/motion/trajectory_analysis.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <vector>

// Its own namespace: compiled in a batch with the other simulator tests, whose helpers share names.
namespace sim_motion_trajectory_test {

using namespace fibrecell::drivers::sim;
using namespace std::chrono_literals;

namespace {

TrajectorySample at(const SimClock& clock, double t_s, double x_mm, double speed,
                    std::uint64_t id) {
    TrajectorySample s;
    s.t_s = t_s;
    s.wall = clock.wall_at(t_s);
    s.tcp_base_mm = {x_mm, 10, 20};
    s.tcp_wobj_mm = {x_mm - 380, 160, -80};
    s.path_mm = x_mm;
    s.speed_mm_s = speed;
    s.segment = id;
    s.joints = {0, 0.1 * x_mm, 0, 0, 0, 0};
    s.source = "FcChunk0001 line " + std::to_string(id);
    return s;
}

}  // namespace

TEST(TrajectoryAnalysis, InterpolatesBetweenNeighbours) {
    const SimClock clock(20);
    const std::vector<TrajectorySample> trajectory{
        at(clock, 1.0, 400, 0, 1), at(clock, 1.5, 420, 40, 1), at(clock, 2.0, 440, 40, 2)};
    const auto s = sample_at(trajectory, clock.wall_at(1.625));
    ASSERT_TRUE(s);
    EXPECT_NEAR(s->t_s, 1.625, 1e-6);
    EXPECT_NEAR(s->path_mm, 425, 1e-4);
    EXPECT_NEAR(s->tcp_base_mm.x(), 425, 1e-4);
    EXPECT_NEAR(s->tcp_wobj_mm.x(), 45, 1e-4);
    EXPECT_NEAR(s->speed_mm_s, 40, 1e-9);
    EXPECT_NEAR(s->joints[1], 42.5, 1e-5);
    EXPECT_EQ(s->segment, 1u);  // the earlier sample's
    EXPECT_EQ(s->source, "FcChunk0001 line 1");

    const auto hit = sample_at(trajectory, clock.wall_at(2.0));
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->segment, 2u);
    EXPECT_EQ(hit->path_mm, 440);
}

TEST(TrajectoryAnalysis, NothingOutsideTheRecording) {
    const SimClock clock(20);
    const std::vector<TrajectorySample> trajectory{at(clock, 1.0, 400, 0, 1),
                                                   at(clock, 2.0, 440, 0, 1)};
    EXPECT_FALSE(sample_at(trajectory, clock.wall_at(0.9)));
    EXPECT_FALSE(sample_at(trajectory, clock.wall_at(2.0) + 1ms));
    EXPECT_FALSE(sample_at({}, clock.wall_at(1.5)));
}

}  // namespace sim_motion_trajectory_test
