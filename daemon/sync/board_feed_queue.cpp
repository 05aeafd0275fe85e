#include "daemon/sync/board_feed_queue.hpp"

#include <algorithm>
#include <chrono>

namespace fibrecell::daemon::sync {

void BoardFeedQueue::acknowledged(double e_mm, double run_s, SteadyClock::time_point at) {
    while (!planned_.empty() && planned_.front().end <= at) planned_.pop_front();
    const SteadyClock::time_point start = planned_.empty() ? at : std::max(at, planned_.back().end);
    const auto run = std::chrono::duration_cast<SteadyClock::duration>(
        std::chrono::duration<double>(std::max(run_s, 0.0)));
    planned_.push_back({start, start + run, e_mm});
}

double BoardFeedQueue::unrun_at(SteadyClock::time_point t) const {
    double unrun = 0;
    for (const Planned& p : planned_) {
        if (t <= p.start) {
            unrun += p.e_mm;
        } else if (t < p.end) {
            unrun += p.e_mm * std::chrono::duration<double>(p.end - t).count() /
                     std::chrono::duration<double>(p.end - p.start).count();
        }
    }
    return unrun;
}

}  // namespace fibrecell::daemon::sync
