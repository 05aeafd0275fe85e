#pragma once
// The engine's self-measurement: per event kind, how long after the robot's counter changed the
// first board command was submitted and acknowledged, and how far the robot had moved meanwhile.
// Summaries (median, p99, max) over a window of the latest samples; the max and count cover all.

#include "drivers/abb/program/print_program.hpp"

#include <cstddef>
#include <deque>
#include <map>
#include <mutex>
#include <vector>

namespace fibrecell::daemon::sync {

struct LatencySummary {
    std::size_t count = 0;  // samples ever recorded
    double median = 0;
    double p99 = 0;
    double max = 0;
};

// Nearest-rank percentile: the smallest sample with at least q of all samples at or below it
// (q in [0, 1]; q = 0.5 of {1, 2, 3, 4} is 2). 0 for no samples.
double percentile(std::vector<double> samples, double q);

// The latest `capacity` samples, plus the count and max of all.
class SampleWindow {
  public:
    explicit SampleWindow(std::size_t capacity = 4096) : capacity_(capacity) {}
    void add(double v);
    LatencySummary summary() const;

  private:
    std::size_t capacity_;
    std::deque<double> latest_;
    std::size_t count_ = 0;
    double max_ = 0;
};

// Per event kind that sends board commands.
struct KindTiming {
    drivers::abb::EventKind kind = drivers::abb::EventKind::layer_end;
    LatencySummary submit_ms;          // counter change (first read) -> first command submitted
    LatencySummary ok_ms;              // counter change (first read) -> its ok from the board
    LatencySummary position_error_mm;  // speed x submit latency: how far the robot ran ahead
};

// Thread-safe: the engine's worker records, status() readers summarise.
class EventTimings {
  public:
    explicit EventTimings(std::size_t window = 4096) : window_(window) {}
    void record_submit(drivers::abb::EventKind kind, double latency_ms, double position_error_mm);
    void record_ok(drivers::abb::EventKind kind, double latency_ms);
    // One entry per kind seen, in EventKind order.
    std::vector<KindTiming> summary() const;

  private:
    struct Samples {
        SampleWindow submit_ms, ok_ms, position_error_mm;
    };
    Samples& samples(drivers::abb::EventKind kind);

    std::size_t window_;
    mutable std::mutex mu_;
    std::map<drivers::abb::EventKind, Samples> by_kind_;
};

}  // namespace fibrecell::daemon::sync
