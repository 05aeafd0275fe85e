#pragma once
// What the service knows about one job, and its state.json (format fibrecell.job/1):
//   {"format": "fibrecell.job/1", "id": 12, "name": "loop", "state": "printing", "reason": "",
//    "submitted_at": "2026-12-01T16:30:00Z", "updated_at": "...", "plan_attempts": 1,
//    "start_when_planned": false, "last_confirmed_event": 0, "journal_lost": false,
//    "submitted_by": "alice", "started_by": "dashboard 10.0.0.7", "planned_at": "...",
//    "started_at": "...", "ended_at": "..."}
// (journal_lost and the *_by / *_at after it may be absent: state files written before them read
// as false and "")

#include "daemon/jobs/job_state.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <stdexcept>
#include <string>

namespace fibrecell::daemon::jobs {

inline constexpr std::string_view job_state_format = "fibrecell.job/1";

// The latest planning or printing progress (not persisted).
struct JobProgress {
    std::string stage;    // planner stage name, "queued", or "printing"
    double fraction = 0;  // of the stage, [0, 1]
};

struct JobRecord {
    std::int64_t id = 0;
    std::string name;
    JobState state = JobState::planning;
    std::string reason;  // why it failed, was aborted, paused on a fault or interrupted
    std::string submitted_at, updated_at;   // UTC, ISO 8601
    int plan_attempts = 0;                  // planning runs begun (a restart during one retries)
    bool start_when_planned = false;        // `fibrecell submit --start`
    std::int64_t last_confirmed_event = 0;  // from the journal; 0: nothing printed
    bool journal_lost = false;  // it had printed and its journal was missing: resume needs a word
    std::string submitted_by, started_by;     // api::CallContext::user; "" when not known
    std::string planned_at, started_at, ended_at;  // UTC, ISO 8601; "" until it happens
    JobProgress progress;
};

class StateFileError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

nlohmann::json to_json(const JobRecord& r);
// Strict: a missing or mistyped key, an unknown state or format throws StateFileError naming the
// key (the caller adds the file).
JobRecord record_from_json(const nlohmann::json& j);

}  // namespace fibrecell::daemon::jobs
