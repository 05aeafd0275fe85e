#pragma once
// Job states and the one table of transitions between them (docs/contracts.md names the states).
//
//   planning     queued for a planning worker or being planned (progress stage "queued" while it
//                waits). -> planned (plan_done), failed (plan_failed), aborted (abort).
//   planned      the plan directory is complete. -> starting (start), planning (replan: a new
//                plan, e.g. for a cell that changed), aborted (abort).
//   starting     pre-flight: devices, heat, RAPID upload. -> printing (print_started), planned or
//                interrupted (start_refused: nothing moved), aborted (abort), failed.
//   printing     the robot runs, the sync engine feeds. -> pausing (pause), paused (faulted: the
//                cell is safe and waits for the operator), completed (print_done),
//                completed_with_warnings (print_short: it ended, but some path fell short of its
//                plan, result.json says where), aborted (abort), failed.
//   pausing      robot stop requested. -> paused (pause_done), aborted (abort), failed.
//   paused       -> printing (resume), aborted (abort), failed.
//   interrupted  the service restarted while the job was starting, printing, pausing or paused;
//                the journal keeps its last confirmed event. -> starting (resume), aborted (abort).
//   completed, completed_with_warnings, aborted, failed: ended; only remove (and replan for
//                failed: plan it again).
// Every starting/printing/pausing/paused job becomes interrupted on a restart (service_restarted).
// A user action that does not fit the state is refused with a message that says what to do.

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::daemon::jobs {

enum class JobState {
    planning,
    planned,
    starting,
    printing,
    pausing,
    paused,
    completed,
    completed_with_warnings,
    aborted,
    failed,
    interrupted,
};

// User actions (API methods job.start ... job.remove) and the service's own events.
enum class JobAction {
    start,
    pause,
    resume,
    abort,
    remove,
    replan,
    // service events
    plan_done,
    plan_failed,
    print_started,
    start_refused,
    pause_done,
    faulted,
    print_done,
    print_short,
    print_failed,
    service_restarted,
};

inline constexpr JobState all_job_states[] = {
    JobState::planning, JobState::planned,    JobState::starting,  JobState::printing,
    JobState::pausing,  JobState::paused,     JobState::completed, JobState::completed_with_warnings,
    JobState::aborted,  JobState::failed,     JobState::interrupted};
inline constexpr JobAction user_actions[] = {JobAction::start,  JobAction::pause,
                                             JobAction::resume, JobAction::abort,
                                             JobAction::remove, JobAction::replan};

std::string_view to_string(JobState s);
std::string_view to_string(JobAction a);
// Throws std::invalid_argument naming the word.
JobState parse_job_state(std::string_view word);

bool is_user_action(JobAction a);
// completed, completed_with_warnings, aborted, failed: nothing more will happen to the job.
bool is_ended(JobState s);
// starting, printing, pausing, paused, interrupted: the job holds the cell (its part is on the
// bed).
bool holds_cell(JobState s);
// pausing, paused, aborted, failed, interrupted: a change into these without a reason of its own
// keeps the one that led there (the fault that paused it). Every other state means all is well
// and clears an old reason.
bool keeps_its_reason(JobState s);

// The states an action may lead to from `from` (two for start_refused); empty: not allowed.
// remove leads to no state: the allowed result is `from` itself (the job is deleted).
std::vector<JobState> allowed_targets(JobState from, JobAction action);

// A user action that does not fit the job's state; the API answers it as a conflict.
class JobConflict : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// "job 12 is printing: abort it first" for a forbidden user action; empty when it is allowed.
std::string refusal(long long job_id, JobState state, JobAction action);

}  // namespace fibrecell::daemon::jobs
