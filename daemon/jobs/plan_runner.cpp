#include "daemon/jobs/plan_runner.hpp"

#include "config/thread_priority.hpp"
#include "daemon/jobs/plan_job.hpp"
#include "daemon/jobs/thread_pool.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <new>

namespace fibrecell::daemon::jobs {

PlanRunner::PlanRunner(JobStore& store, PlanRunnerOptions options)
    : store_(store), options_(std::move(options)) {
    const int n = std::max(1, options_.workers);
    for (int i = 0; i < n; ++i)
        workers_.emplace_back([this] {
            config::name_this_thread("jobs.plan");
            work();
        });
}

PlanRunner::~PlanRunner() {
    stop();
}

void PlanRunner::on_progress(std::function<void(std::int64_t, const JobProgress&)> f) {
    std::lock_guard lock(mu_);
    on_progress_ = std::move(f);
}

void PlanRunner::on_finished(std::function<void(const JobRecord&)> f) {
    std::lock_guard lock(mu_);
    on_finished_ = std::move(f);
}

void PlanRunner::enqueue(std::int64_t id) {
    {
        std::lock_guard lock(mu_);
        queue_.push_back(id);
    }
    store_.set_progress(id, {"queued", 0});
    cv_.notify_all();
}

JobRecord PlanRunner::abort(std::int64_t id) {
    JobRecord r = store_.request(id, JobAction::abort);
    {
        std::lock_guard lock(mu_);
        queue_.erase(std::remove(queue_.begin(), queue_.end(), id), queue_.end());
        if (const auto it = running_.find(id); it != running_.end()) it->second->cancel();
    }
    cv_.notify_all();
    return r;
}

void PlanRunner::wait_idle() {
    std::unique_lock lock(mu_);
    cv_.wait(lock, [&] { return (queue_.empty() && running_.empty()) || stopping_; });
}

void PlanRunner::stop() {
    cancel_all();
    for (auto& t : workers_) t.join();
    workers_.clear();
}

void PlanRunner::cancel_all() {
    {
        std::lock_guard lock(mu_);
        stopping_ = true;
        for (auto& [id, token] : running_) token->cancel();
    }
    cv_.notify_all();
}

bool PlanRunner::join(std::chrono::milliseconds grace) {
    std::vector<std::int64_t> stuck;
    {
        std::unique_lock lock(mu_);
        if (!cv_.wait_for(lock, grace, [&] { return running_.empty(); }))
            for (const auto& [id, token] : running_) stuck.push_back(id);
    }
    if (stuck.empty()) {
        stop();
        return true;
    }
    for (const std::int64_t id : stuck) store_.planning_stopped(id);
    return false;
}

std::string PlanRunner::running_summary() const {
    std::vector<std::int64_t> ids;
    {
        std::lock_guard lock(mu_);
        for (const auto& [id, token] : running_) ids.push_back(id);
    }
    std::string out;
    for (const std::int64_t id : ids) {
        out += (out.empty() ? "job " : ", job ") + std::to_string(id);
        try {
            out += " (stage " + store_.get(id).progress.stage + ")";
        } catch (const std::exception&) {  // removed meanwhile
        }
    }
    return out;
}

void PlanRunner::work() {
    config::lower_thread_priority(options_.planner_nice);
    for (;;) {
        std::int64_t id = 0;
        {
            std::unique_lock lock(mu_);
            cv_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
            if (stopping_) return;
            id = queue_.front();
            queue_.pop_front();
            running_.emplace(id, std::make_shared<planner::CancelToken>());
        }
        try {
            plan_one(id);
        } catch (const std::exception& e) {  // the store could not write the outcome
            spdlog::error("job.plan_outcome_lost job {}: {}", id, e.what());
        }
        {
            std::lock_guard lock(mu_);
            running_.erase(id);
        }
        cv_.notify_all();
    }
}

void PlanRunner::plan_one(std::int64_t id) {
    std::shared_ptr<planner::CancelToken> token;
    std::function<void(std::int64_t, const JobProgress&)> progress_observer;
    std::function<void(const JobRecord&)> finished_observer;
    {
        std::lock_guard lock(mu_);
        token = running_.at(id);
        progress_observer = on_progress_;
        finished_observer = on_finished_;
    }
    std::optional<PlanTicket> ticket;
    try {
        ticket = store_.begin_planning(id);
    } catch (const std::exception& e) {
        spdlog::error("job.plan_failed job {}: cannot prepare: {}", id, e.what());
        if (auto r = store_.apply(id, JobAction::plan_failed, e.what()); r && finished_observer)
            finished_observer(*r);
        return;
    }
    if (!ticket) return;  // aborted or removed while it waited
    spdlog::info("job.planning job {}", id);

    const auto sink = [&](std::string_view stage, double fraction) {
        const JobProgress p{std::string(stage), fraction};
        store_.set_progress(id, p);
        if (progress_observer) progress_observer(id, p);
    };
    PlanRequest request;
    request.job_file = ticket->job_file;
    if (ticket->job) {  // read once, at submit
        request.job = ticket->job->spec;
        request.settings = ticket->job->settings;
    }
    request.out_dir = ticket->plan_dir;
    request.cell = options_.cell;
    request.executor = options_.executor;
    std::optional<JobRecord> result;
    try {
        plan_job(request, {sink, token.get()});
        result = store_.apply(id, JobAction::plan_done);
    } catch (const planner::Cancelled&) {
        bool stopping = false;
        {
            std::lock_guard lock(mu_);
            stopping = stopping_;
        }
        // An abort moved the job already; a shutdown leaves it planning for the next start.
        if (stopping) store_.planning_stopped(id);
        spdlog::info("job.plan_cancelled job {}", id);
        return;
    } catch (const std::bad_alloc&) {
        // The memory a plan takes is bounded by part_limits (docs/service.md, "Memory"); a
        // machine short of it fails this job, and the service and the other jobs go on.
        const std::string why = "planning ran out of memory: the machine could not give the planner "
                                "what this part needs (std::bad_alloc)";
        spdlog::error("job.plan_failed job {}: {}", id, why);
        result = store_.apply(id, JobAction::plan_failed, why);
    } catch (const std::exception& e) {
        spdlog::warn("job.plan_failed job {}: {}", id, e.what());
        result = store_.apply(id, JobAction::plan_failed, e.what());
    }
    if (result && finished_observer) finished_observer(*result);
}

}  // namespace fibrecell::daemon::jobs
