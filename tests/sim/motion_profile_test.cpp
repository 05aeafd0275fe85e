// The look-ahead speed profile on its own: trapezoids and triangles by hand, junction caps, a
// chain of short segments braked as one, a start too fast to brake at the set rate, a
// reorientation between two moves, and the corner factor.
#include "drivers/sim/motion/speed_profile.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

// Its own namespace: compiled in a batch with the other simulator tests, whose helpers share names.
namespace sim_motion_profile_test {

using namespace fibrecell::drivers::sim;

namespace {

constexpr double a = 1000;  // mm/s^2
constexpr double deg = std::numbers::pi / 180;

SpeedProfile plan(const std::vector<ProfileSegment>& chain, const ProfileStart& start = {}) {
    return SpeedProfile(chain, start, a);
}

}  // namespace

TEST(CornerSpeedFactor, FullUpToFiveDegreesThenLinearToNinety) {
    EXPECT_EQ(corner_speed_factor(0), 1);
    EXPECT_EQ(corner_speed_factor(5 * deg), 1);
    EXPECT_NEAR(corner_speed_factor(47.5 * deg), 0.5, 1e-12);
    EXPECT_NEAR(corner_speed_factor(45 * deg), 45.0 / 85, 1e-12);
    EXPECT_EQ(corner_speed_factor(90 * deg), 0);
    EXPECT_EQ(corner_speed_factor(150 * deg), 0);
}

TEST(SpeedProfile, EmptyChainStands) {
    const SpeedProfile p = plan({}, {.t_s = 3});
    EXPECT_TRUE(p.empty());
    EXPECT_EQ(p.end_time(), 3);
}

TEST(SpeedProfile, TrapezoidOnALongSegment) {
    // 100 mm at 50 mm/s: 0.05 s and 1.25 mm to accelerate, the same to brake.
    const SpeedProfile p = plan({{.length_mm = 100, .cruise_mm_s = 50}}, {.t_s = 10});
    EXPECT_NEAR(p.end_time(), 10 + 2.05, 1e-12);
    EXPECT_NEAR(p.at(10.02).position_mm, 0.5 * a * 0.02 * 0.02, 1e-12);
    EXPECT_NEAR(p.at(10.02).speed_mm_s, 20, 1e-12);
    EXPECT_NEAR(p.at(11).position_mm, 1.25 + 50 * 0.95, 1e-9);
    EXPECT_NEAR(p.at(11).speed_mm_s, 50, 1e-12);
    EXPECT_NEAR(p.at(12.04).speed_mm_s, 10, 1e-9);
    EXPECT_NEAR(p.at(12.04).position_mm, 100 - 0.5 * a * 0.01 * 0.01, 1e-9);
    EXPECT_NEAR(p.at(99).position_mm, 100, 1e-12);
    EXPECT_EQ(p.at(99).speed_mm_s, 0);
    EXPECT_NEAR(p.time_at(0, 50), 10 + 0.05 + (50 - 1.25) / 50, 1e-12);
    EXPECT_NEAR(p.time_at(0, 0.2), 10.02, 1e-12);
    EXPECT_NEAR(p.time_at(0, 100), 12.05, 1e-12);
}

TEST(SpeedProfile, TriangleWhenTooShortToReachCruise) {
    // 2 mm < v^2/a = 2.5 mm: peak sqrt(a L) = 44.72 mm/s after sqrt(L/a) s.
    const SpeedProfile p = plan({{.length_mm = 2, .cruise_mm_s = 50}});
    EXPECT_NEAR(p.end_time(), 2 * std::sqrt(2 / a), 1e-12);
    EXPECT_NEAR(p.at(std::sqrt(2 / a)).speed_mm_s, std::sqrt(a * 2), 1e-9);
    EXPECT_NEAR(p.at(std::sqrt(2 / a)).position_mm, 1, 1e-9);
}

TEST(SpeedProfile, JunctionCapSlowsTheCorner) {
    const SpeedProfile p = plan({{.length_mm = 100, .cruise_mm_s = 50, .exit_cap_mm_s = 20},
                                 {.length_mm = 100, .cruise_mm_s = 50}});
    EXPECT_NEAR(p.segment_end(0).speed_mm_s, 20, 1e-12);
    EXPECT_NEAR(p.segment_end(0).position_mm, 100, 1e-12);
    // Braking 50 -> 20 and accelerating 20 -> 50 each take 0.03 s over 1.05 mm.
    const double one = 0.05 + (100 - 1.25 - 1.05) / 50 + 0.03;
    EXPECT_NEAR(p.segment_end_time(0), one, 1e-12);
    EXPECT_NEAR(p.end_time(), 2 * one, 1e-12);
    EXPECT_NEAR(p.segment_start_time(1), one, 1e-12);
}

TEST(SpeedProfile, LooksAheadThroughShortSegments) {
    // Ten collinear 0.1 mm segments move like one 1 mm segment (a triangle), not ten stops.
    std::vector<ProfileSegment> chain(10,
                                      {.length_mm = 0.1, .cruise_mm_s = 50, .exit_cap_mm_s = 50});
    const SpeedProfile p = plan(chain);
    EXPECT_NEAR(p.end_time(), 2 * std::sqrt(1 / a), 1e-12);
    EXPECT_NEAR(p.segment_end(4).speed_mm_s, std::sqrt(2 * a * 0.5), 1e-9);
}

TEST(SpeedProfile, StartsFromTheRobotsPositionAndSpeed) {
    // Mid-segment at cruise: 10 mm left, braked at a over the last 1.25 mm.
    const SpeedProfile p = plan({{.length_mm = 100, .cruise_mm_s = 50}},
                                {.t_s = 1, .position_mm = 90, .speed_mm_s = 50});
    EXPECT_NEAR(p.end_time(), 1 + (10 - 1.25) / 50 + 0.05, 1e-12);
    EXPECT_NEAR(p.at(1.1).position_mm, 95, 1e-12);
    EXPECT_NEAR(p.time_at(0, 80), 1, 1e-12);  // already passed
}

TEST(SpeedProfile, BrakesHarderWhenTheDistanceIsShort) {
    // 50 mm/s with 1 mm to go (braking at a needs 1.25 mm): uniform deceleration 1250 mm/s^2.
    const SpeedProfile p = plan({{.length_mm = 1, .cruise_mm_s = 50}}, {.speed_mm_s = 50});
    EXPECT_NEAR(p.end_time(), 2.0 / 50, 1e-12);
    EXPECT_NEAR(p.at(0.02).speed_mm_s, 25, 1e-9);
}

TEST(SpeedProfile, ReorientationBetweenMovesStartsAndEndsAtRest) {
    const SpeedProfile p = plan({{.length_mm = 10, .cruise_mm_s = 50, .exit_cap_mm_s = 50},
                                 {.dwell_s = 0.5, .exit_cap_mm_s = 50},
                                 {.length_mm = 10, .cruise_mm_s = 50}});
    const double move = 0.05 + (10 - 2.5) / 50 + 0.05;
    EXPECT_EQ(p.segment_end(0).speed_mm_s, 0);
    EXPECT_NEAR(p.segment_end_time(1), move + 0.5, 1e-12);
    EXPECT_NEAR(p.end_time(), 2 * move + 0.5, 1e-12);
    const ProfilePoint turning = p.at(move + 0.2);
    EXPECT_EQ(turning.segment, 1u);
    EXPECT_NEAR(turning.dwell_elapsed_s, 0.2, 1e-12);
    EXPECT_EQ(turning.speed_mm_s, 0);
}

}  // namespace sim_motion_profile_test
