#pragma once
// Prints jobs on the cell, one at a time, on its own thread (docs/service.md): pre-flight and the
// start of a job, then the print's progress, pause, resume, abort and end, each reflected in the
// job store through its transition table and in the job's journal.
//
//   start(id):  job starting -> the plan is loaded from the plan directory and verified
//               (daemon/print/print_plan.hpp: a damaged plan or one for a cell that changed is
//               refused), re-entered after an interruption, the devices connected,
//               PrintSession::start (chunks checked and uploaded, heat-up, FcMain's run) ->
//               printing; a refused start -> back to planned (or interrupted) with the reason,
//               nothing moved.
//   while printing: the engine's confirmed events are journaled (fsync) as they come, progress is
//               reported, a device fault makes the job paused with the reason (the cell is safe:
//               robot held, feed stopped, heaters on) until the operator resumes or aborts.
//   heaters: HeaterPolicy says when they go off (a print's end, a long pause, an idle cell);
//               the runner sends the M104 S0s, and at a service stop too.
//
// What each command and device event does on the cell, held print and recovery included, is the
// recovery table's (recovery.hpp); the runner carries out its steps. Commands come from the
// API's threads and return at once; their outcome is reported through the callback (the job's
// transition, or the reason it could not be done).

#include "daemon/cell/cell_config.hpp"
#include "daemon/jobs/job_store.hpp"
#include "daemon/print/print_plan.hpp"
#include "daemon/print/print_session.hpp"
#include "daemon/devices/cell_devices.hpp"
#include "daemon/printer/heater_policy.hpp"
#include "daemon/printer/recovery.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace fibrecell::daemon::printer {

using devices::CellDevices;

struct PrintRunnerOptions {
    std::chrono::milliseconds connect_timeout{10000};  // devices up at a start
    std::chrono::milliseconds heartbeat_timeout{1000}; // real time: FcMain holds the robot after it
    HeaterPolicyOptions heaters;
    std::chrono::milliseconds poll_period{100};
    int realtime_priority = 20;  // SCHED_FIFO of the sync, serial and Modbus threads; 0: off
    double late_cut_mm = 2.0;    // a cut this far past its place is a shortfall
};

class PrintRunner {
  public:
    // What a command's caller hears: empty on success, else why it could not be done.
    using Done = std::function<void(const std::string& error)>;

    PrintRunner(jobs::JobStore& store, CellDevices& devices, const CellConfig& cell,
                PrintRunnerOptions options = {});
    ~PrintRunner();  // stop()
    PrintRunner(const PrintRunner&) = delete;
    PrintRunner& operator=(const PrintRunner&) = delete;

    // Progress of the job printing (about every poll period; the API rate-limits).
    void on_progress(std::function<void(std::int64_t id, const nlohmann::json& print)> f);
    // A print left the cell and its figures are written (result.json, the journal); before the
    // first start.
    void on_finished(std::function<void(std::int64_t id)> f);
    // The filament the job has taken so far (all runs), each poll it changed, and the layer being
    // printed; `run` tells the job's runs apart (unique across restarts: a re-entry is a new run,
    // its count continuing from the journal's). On the runner's thread, must not block for long.
    // Before the first start.
    struct Feed {
        std::int64_t job = 0;
        std::uint64_t run = 0;
        jobs::JournalUsed used;
        int layer = -1;
    };
    using FeedObserver = std::function<void(const Feed& feed)>;
    void on_feed(FeedObserver f);

    // The job was moved to starting by the store (job.start or job.resume of an interrupted
    // job); the runner takes it from there.
    void start(std::int64_t id, Done done);
    // The job is pausing / was resumed / was aborted in the store; the runner acts on the cell.
    void pause(std::int64_t id, Done done);
    void resume(std::int64_t id, Done done);
    void abort(std::int64_t id, Done done);
    // The cell's E-stop was sent (M112 and the robot's abort request, the cell component's
    // cell.estop): a running print is aborted.
    void abort_for_estop();

    // The job on the cell and its print progress; nullopt when none.
    std::optional<std::int64_t> current_job() const;
    nlohmann::json print_status() const;  // {"job", "progress", "sync"} or {}
    nlohmann::json heater_status() const;  // HeaterPolicy::status

    // Service stopping: a running print is paused (robot stopped, feed stopped) so that the job
    // comes back interrupted and resumable; joins the thread.
    void stop();

    enum class CommandKind { start, pause, resume, abort };

  private:
    struct Command {
        CommandKind kind;
        std::int64_t id;
        Done done;
    };
    struct Active;

    void post(Command c);
    void run();
    void handle(Command& c);
    // What the recovery table is told of the cell and of job `id` (recovery.hpp).
    Situation situation(PrintEvent event, std::int64_t id);
    void carry_out(Step step, std::int64_t id, const std::string& reason = "");
    void fault(Active& a, const std::string& reason);
    void start_job(std::int64_t id);
    void reconnect_board(Active& a);
    void cut_left_fibre(std::int64_t id);
    void save_fibre_fed(Active& a, const sync::MeteringStatus& m);
    jobs::JournalUsed save_used(Active& a);
    void poll_active();
    // `outcome`: how the print ended, for the heaters' log ("completed", "aborted by the
    // operator"); `reason`: result.json's reason (empty: none).
    void finish(const std::string& outcome, const std::string& reason = "");
    void tend_heaters();
    void reconnect_idle_board();
    std::future<drivers::marlin::CommandOutcome> send_heaters_off(const std::string& reason);
    nlohmann::json progress_json() const;  // lock held

    jobs::JobStore& store_;
    CellDevices& devices_;
    CellConfig cell_;
    PrintRunnerOptions options_;
    std::function<void(std::int64_t, const nlohmann::json&)> on_progress_;
    std::function<void(std::int64_t)> on_finished_;
    FeedObserver on_feed_;

    mutable std::mutex mu_;
    std::condition_variable cv_;
    std::deque<Command> commands_;
    std::unique_ptr<Active> active_;
    HeaterPolicy heaters_;
    std::uint64_t last_run_;  // from the clock at construction: unique across restarts
    bool heaters_unreachable_logged_ = false;  // the runner's thread only
    std::optional<std::chrono::steady_clock::time_point> last_idle_reconnect_;  // the same
    bool stopping_ = false;
    std::thread thread_;  // last
};

}  // namespace fibrecell::daemon::printer
