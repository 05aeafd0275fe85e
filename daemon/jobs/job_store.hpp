#pragma once
// The job store: one folder per job under <state_dir>/jobs/<id>/ (docs/jobs.md)
//
//   input/job.yaml, input/...   the job as submitted, its files inline
//   plan/                       the plan directory (docs/contracts.md)
//   state.json                  the job's record, replaced atomically (temp, fsync, rename, fsync)
//   journal.jsonl               the print's events, appended and fsynced one by one
//
// and <state_dir>/next_id, so that ids grow across restarts. Every state change goes through the
// transition table of job_state.hpp; a user action that does not fit is refused with JobConflict
// and changes nothing. Thread-safe; observers run after the store's lock is released.

#include "daemon/jobs/job_input.hpp"
#include "daemon/jobs/job_journal.hpp"
#include "daemon/jobs/job_record.hpp"
#include "daemon/jobs/job_state.hpp"
#include "daemon/print/print_settings.hpp"
#include "planner/job/job_spec.hpp"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace fibrecell::daemon::jobs {

struct JobStoreOptions {
    std::filesystem::path state_dir;  // created if missing
    int max_queued = 16;              // jobs planning or planned (not started); submit refuses more
    int keep_completed = 50;          // ended jobs kept; the oldest beyond are removed
    int plan_retries = 3;             // restarts during a job's planning before it is failed
    // The print's settings for this cell, made once at submit (and read from the plan after
    // it): throws print::SettingsError to refuse the job.
    std::function<print::PrintSettings(const planner::JobSpec&)> settings_for;
};

// A job as the service read it, once, at its submission: the typed job (its files in the job's
// input folder) and the print's settings for this cell. Planning takes it from there.
struct ReadJob {
    planner::JobSpec spec;
    std::optional<print::PrintSettings> settings;  // none when the store has no settings_for
};

// state.json could not be written (a full disk, an I/O error): the change did not happen.
class StateWriteError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

class JobNotFound : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// What load_all() found.
struct LoadReport {
    std::vector<std::int64_t> loaded;       // every job found, in id order
    std::vector<std::int64_t> to_plan;      // planning: hand these to the PlanRunner again
    std::vector<std::int64_t> interrupted;  // were starting/printing/pausing/paused
    std::vector<std::int64_t> failed;       // failed now: unreadable state, retry limit
    std::vector<std::string> warnings;      // leftovers removed, torn journal tails cut
};

// What a planning worker needs.
struct PlanTicket {
    std::int64_t id = 0;
    std::filesystem::path job_file;  // input/job.yaml
    std::filesystem::path plan_dir;  // emptied for this attempt
    // As read at submit; null for a job this run of the service did not take in (it was
    // submitted before a restart): the worker reads job_file.
    std::shared_ptr<const ReadJob> job;
};

class JobStore {
  public:
    explicit JobStore(JobStoreOptions options);
    ~JobStore();

    // Reads every job folder (once, at start-up, before anything else): see docs/jobs.md.
    // A job whose state.json cannot be read is reported failed with the reason; the others load.
    LoadReport load_all();

    // Stores a new job in state planning (progress stage "queued") and returns it. Throws
    // JobInputError / config::ConfigError for a bad job, what settings_for throws for one the cell
    // cannot print (nothing is stored, no id used), and JobConflict when max_queued jobs wait
    // already.
    JobRecord submit(const JobInput& input);

    JobRecord get(std::int64_t id) const;  // throws JobNotFound ("no job 12")
    std::vector<JobRecord> list() const;   // in id order

    // A user action (start, pause, resume, abort, remove, replan). Throws StateWriteError when
    // state.json cannot be written (nothing changed), JobConflict with
    // refusal()'s message, or when another job holds the cell (start, resume), or for a replan of
    // a job whose print had started; JobNotFound. remove deletes the folder and returns the
    // record as it was; replan starts the job's planning afresh (no attempts, no reason).
    // `by` (api::CallContext::user) is kept as the record's started_by for a start or re-entry.
    JobRecord request(std::int64_t id, JobAction action, const std::string& by = {});

    // A service event (plan_done, faulted, ...). `reason` is kept for failed, aborted, paused and
    // interrupted. Returns nullopt (nothing changed) when the table does not allow it from the
    // job's current state, e.g. plan_done for a job aborted meanwhile. Never throws for the
    // disk: when state.json cannot be written the change holds in memory, its reason says "not
    // saved: ...", and the disk keeps the last state it took.
    std::optional<JobRecord> apply(std::int64_t id, JobAction event,
                                   const std::string& reason = {});

    // Planning: the worker takes a job that is still planning (plan_attempts + 1, persisted, plan
    // directory emptied); nullopt when it is no longer planning.
    std::optional<PlanTicket> begin_planning(std::int64_t id);
    // The worker stopped without a result because the service is stopping: the attempt does not
    // count against plan_retries.
    void planning_stopped(std::int64_t id);
    void set_progress(std::int64_t id, const JobProgress& progress);

    // The job's journal, opened on first use (printing). Throws JobNotFound.
    std::shared_ptr<JobJournal> journal(std::int64_t id);

    // The print's progress into state.json (the print runner calls it at every layer): a job whose
    // journal is lost still knows, to the layer, how far it got.
    void confirm_progress(std::int64_t id, std::int64_t last_confirmed_event);

    // A job that had printed and whose journal.jsonl was missing at start-up refuses resume
    // (its part is on the bed; how far it got is known only to the last layer state.json saw):
    // the operator's explicit word lets it resume after state.json's last confirmed event.
    void accept_lost_journal(std::int64_t id);

    // Deletes the plan directory of a job that ended (completed, aborted, failed): never of one
    // planned, queued, printing or interrupted. True when a plan was removed.
    bool remove_plan(std::int64_t id);

    std::filesystem::path job_dir(std::int64_t id) const;
    std::filesystem::path plan_dir(std::int64_t id) const { return job_dir(id) / "plan"; }
    std::filesystem::path input_dir(std::int64_t id) const { return job_dir(id) / "input"; }
    std::int64_t next_id() const;

    // Called after every state change (and on submit), outside the store's lock.
    void on_change(std::function<void(const JobRecord&)> observer);

  private:
    struct Entry {
        JobRecord record;
        std::shared_ptr<JobJournal> journal;
        std::shared_ptr<const ReadJob> read;  // from submit until its planning begins
    };

    Entry& entry(std::int64_t id);              // throws JobNotFound; lock held
    const Entry& entry(std::int64_t id) const;  // throws JobNotFound; lock held
    void persist(const JobRecord& r) const;     // state.json; lock held
    JobRecord change(Entry& e, JobState to, const std::string& reason);  // lock held
    void check_cell_free(std::int64_t id) const;                         // lock held
    void prune_ended();                                                  // lock held
    void remove_folder(std::int64_t id);                                 // lock held
    void notify(const std::vector<JobRecord>& changed);
    std::filesystem::path jobs_root() const { return options_.state_dir / "jobs"; }

    JobStoreOptions options_;
    mutable std::mutex mu_;
    std::map<std::int64_t, Entry> jobs_;
    std::int64_t next_id_ = 1;
    std::function<void(const JobRecord&)> observer_;
};

}  // namespace fibrecell::daemon::jobs
