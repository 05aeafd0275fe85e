#pragma once
// Planning on worker threads: jobs in state planning wait in a queue (progress stage "queued");
// each worker takes one, plans it into its plan directory with plan_job, and moves it to planned,
// or to failed with the reason (a bad mesh, an unreachable target) while the others go on.
// Progress per stage goes to the store (job.get) and to an observer (notifications); abort()
// cancels a queued or running plan.
//
//   PlanRunner runner(store, {.workers = 1});
//   runner.on_progress([&](std::int64_t id, const JobProgress& p) { api.notify(id, p); });
//   for (auto id : store.load_all().to_plan) runner.enqueue(id);
//   runner.enqueue(store.submit(input).id);

#include "daemon/cell/cell_config.hpp"
#include "daemon/jobs/job_store.hpp"
#include "planner/executor.hpp"
#include "planner/progress.hpp"

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace fibrecell::daemon::jobs {

struct PlanRunnerOptions {
    int workers = 1;  // jobs planned at the same time (JobsConfig)
    // Nice value of the workers (the pool's threads take theirs from ThreadPoolOptions):
    // planning takes every core it gets, and a print's sync threads must still run within
    // milliseconds.
    int planner_nice = 10;
    CellConfig cell;                        // the cell the plans are for
    planner::Executor* executor = nullptr;  // the layers of every plan; null: on the worker
};

class PlanRunner {
  public:
    PlanRunner(JobStore& store, PlanRunnerOptions options);
    ~PlanRunner();  // stop()
    PlanRunner(const PlanRunner&) = delete;
    PlanRunner& operator=(const PlanRunner&) = delete;

    // Observers; set before the first enqueue. They run on a worker thread.
    void on_progress(std::function<void(std::int64_t id, const JobProgress&)> f);
    // After a plan ended: planned or failed (the record as stored).
    void on_finished(std::function<void(const JobRecord&)> f);

    // Queues a job that is in state planning (anything else is skipped when its turn comes).
    void enqueue(std::int64_t id);
    // The user's abort of a planning job: the store's transition (throws JobConflict like
    // JobStore::request), then the plan is dropped from the queue or cancelled where it runs.
    JobRecord abort(std::int64_t id);

    // Waits until the queue is empty and no worker plans (tests, clean shutdown).
    void wait_idle();
    // Cancels running plans (their jobs stay planning and are planned again after a restart,
    // without counting as a retry) and joins the workers. Queued jobs stay planning.
    void stop();
    // A stop in two steps, for a service that must end within a deadline: cancel, do the rest
    // of its stop, then wait at most `grace` for the workers to reach a cancel check. False: a
    // worker is still inside one step (a factorisation); its job was put back as above, and
    // the workers still run, so the caller must end the process (std::_Exit) without
    // destroying this runner.
    void cancel_all();
    bool join(std::chrono::milliseconds grace);
    // The jobs a worker is planning now, with their stage (for the log of an unfinished stop).
    std::string running_summary() const;

  private:
    void work();
    void plan_one(std::int64_t id);

    JobStore& store_;
    PlanRunnerOptions options_;
    std::function<void(std::int64_t, const JobProgress&)> on_progress_;
    std::function<void(const JobRecord&)> on_finished_;

    mutable std::mutex mu_;
    std::condition_variable cv_;
    std::deque<std::int64_t> queue_;
    std::map<std::int64_t, std::shared_ptr<planner::CancelToken>> running_;
    bool stopping_ = false;
    std::vector<std::thread> workers_;
};

}  // namespace fibrecell::daemon::jobs
