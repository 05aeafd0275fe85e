#include "drivers/sim/motion/trajectory_analysis.hpp"

#include <algorithm>
#include <chrono>

namespace fibrecell::drivers::sim {

std::optional<TrajectorySample> sample_at(std::span<const TrajectorySample> trajectory,
                                          SimClock::WallClock::time_point wall) {
    if (trajectory.empty() || wall < trajectory.front().wall || wall > trajectory.back().wall)
        return std::nullopt;
    // First sample after `wall`; the one before it is at or before `wall`.
    const auto after = std::upper_bound(
        trajectory.begin(), trajectory.end(), wall,
        [](SimClock::WallClock::time_point w, const TrajectorySample& s) { return w < s.wall; });
    const TrajectorySample& a = *std::prev(after);
    if (after == trajectory.end() || a.wall == wall) return a;
    const TrajectorySample& b = *after;
    const double f = std::chrono::duration<double>(wall - a.wall).count() /
                     std::chrono::duration<double>(b.wall - a.wall).count();
    auto lerp = [f](const auto& x, const auto& y) { return x + f * (y - x); };
    TrajectorySample s = a;
    s.wall = wall;
    s.t_s = lerp(a.t_s, b.t_s);
    s.tcp_base_mm = lerp(a.tcp_base_mm, b.tcp_base_mm);
    s.tcp_wobj_mm = lerp(a.tcp_wobj_mm, b.tcp_wobj_mm);
    s.path_mm = lerp(a.path_mm, b.path_mm);
    s.speed_mm_s = lerp(a.speed_mm_s, b.speed_mm_s);
    for (std::size_t i = 0; i < s.joints.size(); ++i) s.joints[i] = lerp(a.joints[i], b.joints[i]);
    return s;
}

}  // namespace fibrecell::drivers::sim
