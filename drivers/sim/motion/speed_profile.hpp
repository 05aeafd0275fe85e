#pragma once
// The TCP speed along a chain of path segments: one constant acceleration and deceleration, a
// cruise speed per segment, a speed cap at every junction and a standstill at the end of the
// chain, which is how far the simulated controller looks ahead (docs/sim-motion.md). Pure: no
// clock, no threads; times are simulated seconds.

#include <cstddef>
#include <span>
#include <vector>

namespace fibrecell::drivers::sim {

// Junction speed factor of a fly-by corner that turns the path direction by `corner_rad`: 1 up
// to 5 deg, falling linearly to 0 at 90 deg, 0 beyond (a square corner is a stop).
double corner_speed_factor(double corner_rad);

struct ProfileSegment {
    double length_mm = 0;      // arc length; 0 for a pure reorientation or a no-op move
    double cruise_mm_s = 0;    // top speed along it (> 0 when length_mm > 0)
    double dwell_s = 0;        // duration of a pure reorientation (length 0): entered and left
                               // at standstill
    double exit_cap_mm_s = 0;  // highest speed at its end (the junction to the next segment)
};

// The robot when the profile is planned.
struct ProfileStart {
    double t_s = 0;          // [s]
    double position_mm = 0;  // along the first segment
    double speed_mm_s = 0;
    double dwell_elapsed_s = 0;  // of the first segment, when it is a reorientation
};

// The robot at one instant of the profile.
struct ProfilePoint {
    std::size_t segment = 0;  // index into the planned segments
    double position_mm = 0;   // along that segment
    double speed_mm_s = 0;
    double dwell_elapsed_s = 0;  // of that segment, when it is a reorientation
};

class SpeedProfile {
  public:
    SpeedProfile() = default;  // nothing planned: the robot stands
    // Plans `segments` (the first one entered at `start`) with acceleration `accel_mm_s2`
    // [mm/s^2]: the fastest profile under the cruise speeds and junction caps that stands still
    // at the end of the last segment. A start faster than the chain allows (never so in the
    // simulator's own use) brakes harder than `accel_mm_s2`.
    SpeedProfile(std::span<const ProfileSegment> segments, const ProfileStart& start,
                 double accel_mm_s2);

    bool empty() const { return segments_.empty(); }
    std::size_t segment_count() const { return segments_.size(); }
    double start_time() const { return start_t_; }
    double end_time() const { return segments_.empty() ? start_t_ : segments_.back().t_end; }

    // The robot at time `t_s` [s], clamped to [start_time(), end_time()]; requires !empty().
    ProfilePoint at(double t_s) const;
    // When the robot enters / leaves segment `i` [s], and the robot as it leaves it.
    double segment_start_time(std::size_t i) const { return segments_[i].t_start; }
    double segment_end_time(std::size_t i) const { return segments_[i].t_end; }
    ProfilePoint segment_end(std::size_t i) const;
    // When the TCP reaches `position_mm` along segment `i` (a length > 0 segment) [s]; the
    // segment's start time for a position the robot had passed when the profile was planned.
    double time_at(std::size_t i, double position_mm) const;

  private:
    // Constant acceleration from (t0, s0, v0) for `duration` [s].
    struct Phase {
        std::size_t segment = 0;
        double t0 = 0, s0 = 0, v0 = 0, accel = 0, duration = 0;
        bool dwell = false;  // a pure reorientation
        double dwell0 = 0;   // reorientation time already done at t0
    };
    struct Span {
        double t_start = 0, t_end = 0;
        std::size_t first_phase = 0, phase_count = 0;
        ProfilePoint end;  // the robot as it leaves the segment
    };
    ProfilePoint point_of(const Phase& p, double t_s) const;

    double start_t_ = 0;
    ProfilePoint start_point_;
    std::vector<Phase> phases_;
    std::vector<Span> segments_;
};

}  // namespace fibrecell::drivers::sim
