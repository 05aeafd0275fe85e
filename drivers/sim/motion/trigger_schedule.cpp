#include "drivers/sim/motion/trigger_schedule.hpp"

#include <algorithm>
#include <tuple>

namespace fibrecell::drivers::sim {
namespace {

constexpr double stop_tolerance_mm = 1e-6;

// Path order; triggers at one position in the order they were placed.
bool path_order(double a_mm, std::uint64_t a_seg, std::size_t a_i, double b_mm, std::uint64_t b_seg,
                std::size_t b_i) {
    return std::tie(a_mm, a_seg, a_i) < std::tie(b_mm, b_seg, b_i);
}

}  // namespace

void TriggerSchedule::plan(const std::deque<PathSegment>& queue, const SpeedProfile& profile,
                           double t_s, double position_mm, std::optional<double> stop_at_mm) {
    due_.clear();
    for (std::size_t k = 0; k < profile.segment_count() && k < queue.size(); ++k) {
        const PathSegment& seg = queue[k];
        for (std::size_t i = 0; i < seg.triggers.size(); ++i) {
            const PlacedTrigger& trig = seg.triggers[i];
            if (trig.fired) continue;
            const double path_mm = seg.path_start_mm + trig.position_mm;
            double reach_t = 0;
            if (seg.reorientation()) {
                reach_t =
                    trig.at_start ? profile.segment_start_time(k) : profile.segment_end_time(k);
            } else {
                if (stop_at_mm && path_mm > *stop_at_mm + stop_tolerance_mm) continue;
                reach_t = k == 0 && trig.position_mm <= position_mm
                              ? t_s
                              : profile.time_at(k, trig.position_mm);
            }
            // A negative lag would fire after the segment is gone: it counts as none.
            due_.push_back({.fire_t_s = reach_t - std::max(0.0, trig.trigger.lag_s),
                            .path_mm = path_mm,
                            .segment = seg.id,
                            .index = i});
        }
    }
    std::sort(due_.begin(), due_.end(), [](const Due& a, const Due& b) {
        return a.fire_t_s < b.fire_t_s ||
               (a.fire_t_s == b.fire_t_s &&
                path_order(a.path_mm, a.segment, a.index, b.path_mm, b.segment, b.index));
    });
}

std::vector<std::function<void()>> TriggerSchedule::take_due(double t_s,
                                                             std::deque<PathSegment>& queue) {
    std::vector<Due> now;
    while (!due_.empty() && due_.front().fire_t_s <= t_s) {
        now.push_back(due_.front());
        due_.pop_front();
    }
    // Several due in one tick (a lagged one may overtake a plain one): in path order.
    std::sort(now.begin(), now.end(), [](const Due& a, const Due& b) {
        return path_order(a.path_mm, a.segment, a.index, b.path_mm, b.segment, b.index);
    });
    std::vector<std::function<void()>> fire;
    for (const Due& d : now) {
        const auto seg =
            std::lower_bound(queue.begin(), queue.end(), d.segment,
                             [](const PathSegment& s, std::uint64_t id) { return s.id < id; });
        if (seg == queue.end() || seg->id != d.segment || d.index >= seg->triggers.size()) continue;
        PlacedTrigger& trig = seg->triggers[d.index];
        if (trig.fired) continue;
        trig.fired = true;
        if (trig.trigger.fire) fire.push_back(std::move(trig.trigger.fire));
    }
    return fire;
}

}  // namespace fibrecell::drivers::sim
