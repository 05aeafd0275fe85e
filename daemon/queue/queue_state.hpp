#pragma once
// What the print queue keeps across restarts (docs/queue.md): the queued jobs in print order,
// whether the queue is paused and why, and the cell's bed: clear, or holding the part of a job
// that printed on it. One file, <state_dir>/queue.json, replaced durably at every change.

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace fibrecell::daemon::queue {

struct Bed {
    bool clear = true;
    std::int64_t job = 0;  // whose part is on it (0: not known, its file was unreadable)
    std::string outcome;   // how that print went: printing, completed, aborted, interrupted, ...
    std::string since;     // UTC, ISO 8601
};

struct QueueState {
    std::vector<std::int64_t> jobs;  // in print order, the next first
    bool paused = false;
    std::string paused_reason;
    Bed bed;
};

nlohmann::json to_json(const QueueState& s);

// The file's state; a missing file is a new cell (empty queue, clear bed). Throws
// std::runtime_error naming the file and what is wrong with it.
QueueState load_queue_state(const std::filesystem::path& file);

// Replaces the file durably (config/durable_file.hpp); throws std::system_error.
void save_queue_state(const std::filesystem::path& file, const QueueState& s);

}  // namespace fibrecell::daemon::queue
