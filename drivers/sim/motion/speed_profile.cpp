#include "drivers/sim/motion/speed_profile.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fibrecell::drivers::sim {

double corner_speed_factor(double corner_rad) {
    constexpr double full_speed = 5 * std::numbers::pi / 180;
    constexpr double stop = 90 * std::numbers::pi / 180;
    if (corner_rad <= full_speed) return 1;
    if (corner_rad >= stop) return 0;
    return (stop - corner_rad) / (stop - full_speed);
}

SpeedProfile::SpeedProfile(std::span<const ProfileSegment> segments, const ProfileStart& start,
                           double accel_mm_s2)
    : start_t_(start.t_s) {
    const std::size_t n = segments.size();
    if (n == 0) return;
    const double a = accel_mm_s2;
    auto is_dwell = [&](std::size_t i) { return segments[i].dwell_s > 0; };
    std::vector<double> remaining(n);
    for (std::size_t i = 0; i < n; ++i)
        remaining[i] =
            is_dwell(i) ? 0
                        : std::max(0.0, segments[i].length_mm - (i == 0 ? start.position_mm : 0));

    // Backward pass: the fastest speed at each junction from which the rest of the chain can
    // still be braked in time.
    std::vector<double> exit_speed(n, 0);
    for (std::size_t i = n - 1; i-- > 0;) {
        if (is_dwell(i) || is_dwell(i + 1)) continue;  // reorientations start and end at rest
        exit_speed[i] =
            std::min(segments[i].exit_cap_mm_s,
                     std::sqrt(exit_speed[i + 1] * exit_speed[i + 1] + 2 * a * remaining[i + 1]));
    }

    // Forward pass: accelerate, cruise, brake within each segment.
    double t = start.t_s;
    double v = is_dwell(0) ? 0 : start.speed_mm_s;
    segments_.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        Span span{.t_start = t, .first_phase = phases_.size()};
        const double s_in = i == 0 ? start.position_mm : 0;
        auto add = [&](double s0, double v0, double accel, double duration, bool dwell,
                       double dwell0) {
            if (duration <= 0) return;
            phases_.push_back({.segment = i,
                               .t0 = t,
                               .s0 = s0,
                               .v0 = v0,
                               .accel = accel,
                               .duration = duration,
                               .dwell = dwell,
                               .dwell0 = dwell0});
            t += duration;
        };
        if (is_dwell(i)) {
            const double done = i == 0 ? start.dwell_elapsed_s : 0;
            add(0, 0, 0, segments[i].dwell_s - done, true, done);
            span.end = {.segment = i, .dwell_elapsed_s = segments[i].dwell_s};
            v = 0;
        } else {
            const double r = remaining[i];
            const double w = std::min(exit_speed[i], std::sqrt(v * v + 2 * a * r));
            if (v * v > w * w + 2 * a * r) {
                // Entered too fast for the distance left: brake harder than `a` to make it.
                if (r > 0) add(s_in, v, (w * w - v * v) / (2 * r), 2 * r / (v + w), false, 0);
            } else {
                const double cruise = std::max({segments[i].cruise_mm_s, v, w});
                const double peak =
                    std::max({std::min(cruise, std::sqrt((2 * a * r + v * v + w * w) / 2)), v, w});
                const double d_up = (peak * peak - v * v) / (2 * a);
                const double d_down = (peak * peak - w * w) / (2 * a);
                const double d_cruise = std::max(0.0, r - d_up - d_down);
                add(s_in, v, a, (peak - v) / a, false, 0);
                add(s_in + d_up, peak, 0, peak > 0 ? d_cruise / peak : 0, false, 0);
                add(s_in + d_up + d_cruise, peak, -a, (peak - w) / a, false, 0);
            }
            span.end = {.segment = i, .position_mm = s_in + r, .speed_mm_s = w};
            v = w;
        }
        span.t_end = t;
        span.phase_count = phases_.size() - span.first_phase;
        segments_.push_back(span);
    }
    start_point_ = {.position_mm = start.position_mm,
                    .speed_mm_s = is_dwell(0) ? 0 : start.speed_mm_s,
                    .dwell_elapsed_s = is_dwell(0) ? start.dwell_elapsed_s : 0};
}

ProfilePoint SpeedProfile::point_of(const Phase& p, double t_s) const {
    const double tau = std::clamp(t_s - p.t0, 0.0, p.duration);
    return {.segment = p.segment,
            .position_mm = p.s0 + p.v0 * tau + 0.5 * p.accel * tau * tau,
            .speed_mm_s = std::max(0.0, p.v0 + p.accel * tau),
            .dwell_elapsed_s = p.dwell ? p.dwell0 + tau : 0};
}

ProfilePoint SpeedProfile::at(double t_s) const {
    if (t_s >= end_time()) return segments_.back().end;
    if (t_s <= start_t_ || phases_.empty()) return start_point_;
    const auto next = std::upper_bound(phases_.begin(), phases_.end(), t_s,
                                       [](double t, const Phase& p) { return t < p.t0; });
    return point_of(*std::prev(next), t_s);
}

ProfilePoint SpeedProfile::segment_end(std::size_t i) const {
    return segments_[i].end;
}

double SpeedProfile::time_at(std::size_t i, double position_mm) const {
    const Span& span = segments_[i];
    double t = span.t_start;
    for (std::size_t k = span.first_phase; k < span.first_phase + span.phase_count; ++k) {
        const Phase& p = phases_[k];
        if (position_mm < p.s0) break;
        // s0 + v0*tau + accel*tau^2/2 = position, in the form that stays exact as v0 -> 0.
        const double d = position_mm - p.s0;
        const double disc = p.v0 * p.v0 + 2 * p.accel * d;
        const double denominator = p.v0 + std::sqrt(std::max(0.0, disc));
        const double tau = disc < 0 ? p.duration : denominator > 0 ? 2 * d / denominator : 0;
        t = p.t0 + std::min(tau, p.duration);
    }
    return t;
}

}  // namespace fibrecell::drivers::sim
