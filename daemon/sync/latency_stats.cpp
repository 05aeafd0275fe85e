#include "daemon/sync/latency_stats.hpp"

#include <algorithm>
#include <cmath>

namespace fibrecell::daemon::sync {

double percentile(std::vector<double> samples, double q) {
    if (samples.empty()) return 0;
    const auto n = samples.size();
    const auto rank = static_cast<std::size_t>(std::ceil(std::clamp(q, 0.0, 1.0) * static_cast<double>(n)));
    const auto k = rank == 0 ? 0 : rank - 1;
    std::nth_element(samples.begin(), samples.begin() + static_cast<std::ptrdiff_t>(k), samples.end());
    return samples[k];
}

void SampleWindow::add(double v) {
    if (capacity_ > 0) {
        if (latest_.size() == capacity_) latest_.pop_front();
        latest_.push_back(v);
    }
    max_ = count_ == 0 ? v : std::max(max_, v);
    ++count_;
}

LatencySummary SampleWindow::summary() const {
    const std::vector<double> v(latest_.begin(), latest_.end());
    return {count_, percentile(v, 0.5), percentile(v, 0.99), max_};
}

EventTimings::Samples& EventTimings::samples(drivers::abb::EventKind kind) {
    auto it = by_kind_.find(kind);
    if (it == by_kind_.end())
        it = by_kind_.emplace(kind, Samples{SampleWindow(window_), SampleWindow(window_),
                                            SampleWindow(window_)}).first;
    return it->second;
}

void EventTimings::record_submit(drivers::abb::EventKind kind, double latency_ms,
                                 double position_error_mm) {
    std::lock_guard lock(mu_);
    Samples& s = samples(kind);
    s.submit_ms.add(latency_ms);
    s.position_error_mm.add(position_error_mm);
}

void EventTimings::record_ok(drivers::abb::EventKind kind, double latency_ms) {
    std::lock_guard lock(mu_);
    samples(kind).ok_ms.add(latency_ms);
}

std::vector<KindTiming> EventTimings::summary() const {
    std::lock_guard lock(mu_);
    std::vector<KindTiming> out;
    for (const auto& [kind, s] : by_kind_)
        out.push_back({kind, s.submit_ms.summary(), s.ok_ms.summary(), s.position_error_mm.summary()});
    return out;
}

}  // namespace fibrecell::daemon::sync
