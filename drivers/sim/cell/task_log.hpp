#pragma once
// The simulated task's messages (TPWrite, run-time errors, stops) with their simulated and real
// time: kept for tests (bounded), passed on to a sink (the program's log), waited on.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace fibrecell::drivers::sim {

struct TaskLogEntry {
    double t_s = 0;  // simulated time
    std::chrono::steady_clock::time_point wall;
    std::string text;
};

class TaskLog {
  public:
    explicit TaskLog(std::function<void(const TaskLogEntry&)> sink = {}, std::size_t max = 10'000)
        : sink_(std::move(sink)), max_(max) {}

    void add(TaskLogEntry e) {
        {
            std::lock_guard lock(mu_);
            entries_.push_back(e);
            if (entries_.size() > max_) entries_.pop_front();
        }
        changed_.notify_all();
        if (sink_) sink_(e);
    }

    std::vector<TaskLogEntry> entries() const {
        std::lock_guard lock(mu_);
        return {entries_.begin(), entries_.end()};
    }

    // Waits until an entry contains `text`; false on timeout.
    bool wait_for(const std::string& text, std::chrono::milliseconds timeout) const {
        std::unique_lock lock(mu_);
        return changed_.wait_for(lock, timeout, [&] {
            for (const TaskLogEntry& e : entries_)
                if (e.text.find(text) != std::string::npos) return true;
            return false;
        });
    }

  private:
    std::function<void(const TaskLogEntry&)> sink_;
    std::size_t max_;
    mutable std::mutex mu_;
    mutable std::condition_variable changed_;
    std::deque<TaskLogEntry> entries_;
};

}  // namespace fibrecell::drivers::sim
