#include "daemon/queue/queue_component.hpp"

#include "config/utc_time.hpp"
#include "daemon/api/api_error.hpp"
#include "daemon/api/params.hpp"
#include "daemon/jobs/job_api.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <limits>
#include <system_error>

namespace fibrecell::daemon::queue {

using api::ApiError;
using api::CallContext;
using jobs::as_api;
using jobs::JobRecord;
using jobs::JobState;
using nlohmann::json;

namespace {

bool queueable(JobState s) { return s == JobState::planning || s == JobState::planned; }

// Ends the queue cannot go past without the operator's word.
bool needs_a_decision(JobState s) {
    return s == JobState::aborted || s == JobState::failed || s == JobState::interrupted;
}

// The bed's job is still on the cell (its print runs or holds): nothing else can start anyway.
bool still_on_the_cell(const std::string& outcome) {
    return outcome == "starting" || outcome == "printing" || outcome == "pausing" ||
           outcome == "paused";
}

std::string job_name(std::int64_t id) { return "job " + std::to_string(id); }

std::int64_t job_param(api::ParamReader& p) {
    if (!p.has("job")) p.fail("job", "is required (a job id)");
    return p.integer_or("job", 0, 1, std::numeric_limits<std::int64_t>::max());
}

}  // namespace

QueueComponent::QueueComponent(jobs::JobsComponent& jobs, printer::PrinterComponent& printer,
                               devices::CellComponent& cell, const CellConfig& cell_config,
                               QueueConfig config)
    : jobs_(jobs), printer_(printer), config_(config),
      file_(std::filesystem::path(cell_config.state_dir) / "queue.json") {
    printer_.add_start_gate([this](const JobRecord& r) { return held_by_bed(r); });
    jobs_.on_change([this](const JobRecord& r) { job_changed(r); });
    cell.add_status_part([this](json& status) {
        std::lock_guard lock(mu_);
        const json v = view();
        status["bed"] = v["bed"];
        status["queue"] = {{"jobs", state_.jobs.size()}, {"paused", state_.paused}};
    });
}

void QueueComponent::add_admission_check(AdmissionCheck check) {
    admission_checks_.push_back(std::move(check));
}

std::vector<std::int64_t> QueueComponent::queued() const {
    std::lock_guard lock(mu_);
    return state_.jobs;
}

std::optional<std::string> QueueComponent::held_by_bed(const JobRecord& r) const {
    std::lock_guard lock(mu_);
    const Bed& bed = state_.bed;
    if (bed.clear) return std::nullopt;
    // A job that cannot start anyway hears the store's own reason (it is completed; another job
    // is on the cell); the interrupted job goes on on its own part.
    if (r.state != JobState::planned && r.state != JobState::interrupted) return std::nullopt;
    if (bed.job == r.id && r.state == JobState::interrupted) return std::nullopt;
    if (bed.job > 0 && still_on_the_cell(bed.outcome)) return std::nullopt;
    if (bed.job > 0 && bed.outcome == "interrupted")
        return job_name(bed.job) + " is interrupted with its part on the bed: resume it, or abort it "
                                   "and take the part off (`fibrecell clear`)";
    const std::string what = bed.job > 0 ? job_name(bed.job) + "'s part (" + bed.outcome + " at " +
                                               bed.since + ") is on the bed"
                                         : "the queue's file was unreadable at start-up (" +
                                               bed.since + "): the bed was not seen clear";
    return "the cell is not clear: " + what +
           "; take the part off, then say so with `fibrecell clear`";
}

void QueueComponent::register_endpoints(component::Endpoints& endpoints) {
    endpoints.control_method("queue.list", [this](const json& params, const CallContext& ctx) {
        api::ParamReader(ctx.method, params).finish();
        std::lock_guard lock(mu_);
        return view();
    });

    endpoints.method("queue.add", [this](const json& params, const CallContext& ctx) {
        {
            api::ParamReader p(ctx.method, params);
            const std::int64_t id = job_param(p);
            std::lock_guard lock(mu_);
            const auto n = static_cast<std::int64_t>(state_.jobs.size());
            const std::int64_t position = p.integer_or("position", n + 1, 1, n + 1);
            p.finish();
            const JobRecord r = as_api([&] { return jobs_.store().get(id); });
            const auto at = std::find(state_.jobs.begin(), state_.jobs.end(), id);
            if (at != state_.jobs.end())
                throw ApiError::conflict(job_name(id) + " is queued already, at position " +
                                         std::to_string(at - state_.jobs.begin() + 1));
            if (!queueable(r.state))
                throw ApiError::conflict(job_name(id) + " is " + std::string(to_string(r.state)) +
                                         ": only a job planning or planned can be queued");
            for (const AdmissionCheck& check : admission_checks_)
                if (const auto why = check(r))
                    throw ApiError::conflict(job_name(id) + " cannot be queued: " + *why);
            refuse_before_a_starting_head(position);
            const QueueState before = state_;
            state_.jobs.insert(state_.jobs.begin() + (position - 1), id);
            commit(before);
            spdlog::info("queue.added {} at {} by {}", job_name(id), position, ctx.peer);
        }
        return next_if_due_then_view();
    });

    endpoints.method("queue.move", [this](const json& params, const CallContext& ctx) {
        {
            api::ParamReader p(ctx.method, params);
            std::lock_guard lock(mu_);
            std::size_t from = 0;
            const std::int64_t id = queued_job(p, &from);
            if (!p.has("position")) p.fail("position", "is required (1 is the next to print)");
            const auto n = static_cast<std::int64_t>(state_.jobs.size());
            const std::int64_t to = p.integer_or("position", 1, 1, n);
            p.finish();
            if (starting_.contains(id))
                throw ApiError::conflict(job_name(id) + " is starting: it keeps its place");
            refuse_before_a_starting_head(to);
            const QueueState before = state_;
            state_.jobs.erase(state_.jobs.begin() + static_cast<std::ptrdiff_t>(from));
            state_.jobs.insert(state_.jobs.begin() + (to - 1), id);
            commit(before);
            spdlog::info("queue.moved {} to {} by {}", job_name(id), to, ctx.peer);
        }
        return next_if_due_then_view();  // a planned job may now be next
    });

    endpoints.method("queue.remove", [this](const json& params, const CallContext& ctx) {
        {
            api::ParamReader p(ctx.method, params);
            std::lock_guard lock(mu_);
            std::size_t at = 0;
            const std::int64_t id = queued_job(p, &at);
            p.finish();
            if (starting_.contains(id))
                throw ApiError::conflict(job_name(id) + " is starting: abort it to stop it");
            const QueueState before = state_;
            state_.jobs.erase(state_.jobs.begin() + static_cast<std::ptrdiff_t>(at));
            commit(before);
            spdlog::info("queue.removed {} by {}", job_name(id), ctx.peer);
        }
        return next_if_due_then_view();
    });

    endpoints.method("queue.pause", [this](const json& params, const CallContext& ctx) {
        api::ParamReader(ctx.method, params).finish();
        std::lock_guard lock(mu_);
        if (!state_.paused) {
            const QueueState before = state_;
            state_.paused = true;
            state_.paused_reason = "paused by " + ctx.peer;
            commit(before);
            spdlog::info("queue.paused by {}", ctx.peer);
        }
        return view();
    });

    endpoints.method("queue.resume", [this](const json& params, const CallContext& ctx) {
        api::ParamReader(ctx.method, params).finish();
        {
            std::lock_guard lock(mu_);
            if (state_.paused) {
                const QueueState before = state_;
                state_.paused = false;
                state_.paused_reason.clear();
                commit(before);
                spdlog::info("queue.resumed by {}", ctx.peer);
            }
        }
        return next_if_due_then_view();
    });

    // The operator's "print the next one now", in either auto_start mode; the gates have their
    // say (a bed that is not clear refuses it).
    endpoints.method("queue.next", [this](const json& params, const CallContext& ctx) {
        api::ParamReader(ctx.method, params).finish();
        std::int64_t next = 0;
        {
            std::lock_guard lock(mu_);
            drop_gone_jobs();
            if (state_.jobs.empty()) throw ApiError::conflict("the queue is empty");
            next = state_.jobs.front();
            const JobRecord r = as_api([&] { return jobs_.store().get(next); });
            if (r.state != JobState::planned)
                throw ApiError::conflict(job_name(next) + ", the next in the queue, is " +
                                         std::string(to_string(r.state)) + ", not planned");
            queue_started_ = next;
        }
        printer_.start_print(next, ctx.user);
        spdlog::info("queue.next {} started by {}", job_name(next), ctx.peer);
        std::lock_guard lock(mu_);
        return view();
    });

    // Not a control method: with auto_start after_clear it starts a print.
    endpoints.method("cell.clear", [this](const json& params, const CallContext& ctx) {
        api::ParamReader(ctx.method, params).finish();
        {
            std::lock_guard lock(mu_);
            for (const JobRecord& r : jobs_.store().list()) {
                if (r.state == JobState::interrupted)
                    throw ApiError::conflict(job_name(r.id) + " is interrupted with its part on the "
                                             "bed: resume it (`fibrecell resume " +
                                             std::to_string(r.id) + "`) or abort it first");
                if (jobs::holds_cell(r.state))
                    throw ApiError::conflict(job_name(r.id) + " is " + std::string(to_string(r.state)) +
                                             " on the cell: clear the bed once it has ended");
            }
            if (!state_.bed.clear) {
                const QueueState before = state_;
                const std::string was = state_.bed.job > 0 ? job_name(state_.bed.job) + "'s part"
                                                           : "not known what";
                state_.bed = {};
                commit(before);
                spdlog::info("cell.cleared by {} ({} was on the bed)", ctx.peer, was);
            }
        }
        return next_if_due_then_view();
    });

    endpoints.event(api::notify::queue);
    endpoints_ = endpoints;
}

json QueueComponent::next_if_due_then_view() {
    start_next_if_due();
    std::lock_guard lock(mu_);
    return view();
}

void QueueComponent::refuse_before_a_starting_head(std::int64_t position) const {
    if (position == 1 && !state_.jobs.empty() && starting_.contains(state_.jobs.front()))
        throw ApiError::conflict(job_name(state_.jobs.front()) +
                                 ", the next in the queue, is starting: nothing goes before it now");
}

std::int64_t QueueComponent::queued_job(api::ParamReader& p, std::size_t* position) {
    const std::int64_t id = job_param(p);
    const auto at = std::find(state_.jobs.begin(), state_.jobs.end(), id);
    if (at != state_.jobs.end()) {
        *position = static_cast<std::size_t>(at - state_.jobs.begin());
        return id;
    }
    const JobRecord r = as_api([&] { return jobs_.store().get(id); });
    throw ApiError::conflict(job_name(id) + " is " + std::string(to_string(r.state)) +
                             ", not queued");
}

void QueueComponent::drop_gone_jobs() {
    bool dropped = false;
    std::erase_if(state_.jobs, [&](std::int64_t id) {
        try {
            jobs_.store().get(id);
            return false;
        } catch (const jobs::JobNotFound&) {
            spdlog::warn("queue.left {}: it was removed", job_name(id));
            dropped = true;
            return true;
        }
    });
    if (dropped) changed();
}

void QueueComponent::start() {
    std::lock_guard lock(mu_);
    try {
        state_ = load_queue_state(file_);
    } catch (const std::exception& e) {
        // The safe side: nothing starts until the operator has looked at the bed. A copy is kept
        // (the new state replaces the file below).
        std::filesystem::path aside = file_;
        aside += ".unreadable";
        std::error_code ec;
        std::filesystem::copy_file(file_, aside, std::filesystem::copy_options::overwrite_existing, ec);
        spdlog::error("queue.unreadable {}; kept as {}; the queue starts empty and the cell not "
                      "clear",
                      e.what(), aside.string());
        state_ = {};
        state_.bed = {.clear = false, .job = 0, .outcome = "unknown", .since = config::utc_now()};
    }
    // What changed while the service was down: queued jobs that went away or on, and the print
    // on the bed (a print the service did not see end is interrupted now).
    jobs::JobStore& store = jobs_.store();
    std::erase_if(state_.jobs, [&](std::int64_t id) {
        try {
            const JobRecord r = store.get(id);
            if (queueable(r.state)) return false;
            spdlog::warn("queue.left {}: {}", job_name(id), to_string(r.state));
        } catch (const jobs::JobNotFound&) {
            spdlog::warn("queue.left {}: it is gone", job_name(id));
        }
        return true;
    });
    Bed& bed = state_.bed;
    if (!bed.clear && bed.job > 0) {
        try {
            const JobRecord r = store.get(bed.job);
            const std::string now(to_string(r.state));
            if (now != bed.outcome && needs_a_decision(r.state)) {
                state_.paused = true;
                state_.paused_reason = job_name(r.id) + " " + now;
            }
            bed.outcome = now;
        } catch (const jobs::JobNotFound&) {
            bed.outcome = "removed";
        }
    }
    // An interrupted job's part is on the bed whatever the file said (it was lost, or written
    // before the print began).
    for (const JobRecord& r : store.list()) {
        if (r.state != JobState::interrupted || (!bed.clear && bed.job == r.id)) continue;
        if (!bed.clear && bed.job > 0) continue;  // another part is there: the operator decides
        bed = {.clear = false, .job = r.id, .outcome = "interrupted", .since = config::utc_now()};
        state_.paused = true;
        state_.paused_reason = job_name(r.id) + " interrupted";
    }
    spdlog::info("queue.loaded {} jobs, {}{}", state_.jobs.size(),
                 bed.clear ? "the cell clear" : "the cell not clear",
                 state_.paused ? ", paused: " + state_.paused_reason : "");
    changed();
}

void QueueComponent::serve() { start_next_if_due(); }

void QueueComponent::job_changed(const JobRecord& r) {
    bool may_start_next = false;
    {
        std::lock_guard lock(mu_);
        bool touched = false;
        const auto at = std::find(state_.jobs.begin(), state_.jobs.end(), r.id);
        const bool queued = at != state_.jobs.end();
        const bool was_starting = starting_.contains(r.id);
        // Notifications of one job may come from two threads (the API's abort, the runner's
        // progress) out of order: what the bed says is the store's state now.
        JobState now = r.state;
        try {
            now = jobs_.store().get(r.id).state;
        } catch (const jobs::JobNotFound&) {
        }

        // A start puts the job's part on the bed (the pre-flight may move the head already); a
        // start the cell refused before anything moved (back to planned) takes it off again.
        if (r.state == JobState::starting && (state_.bed.clear || state_.bed.job != r.id)) {
            started_on_clear_ = state_.bed.clear ? r.id : 0;
            state_.bed = {.clear = false, .job = r.id, .outcome = "starting", .since = config::utc_now()};
            touched = true;
        }
        if (!state_.bed.clear && state_.bed.job == r.id) {
            const std::string outcome(to_string(now));
            if (now == JobState::planned) {
                if (started_on_clear_ == r.id) {
                    state_.bed = {};
                    touched = true;
                }
            } else if (outcome != state_.bed.outcome) {
                state_.bed.outcome = outcome;
                state_.bed.since = config::utc_now();
                touched = true;
                // An aborted, failed or interrupted print leaves the queue paused until the
                // operator decides.
                if (needs_a_decision(now)) {
                    state_.paused = true;
                    state_.paused_reason =
                        job_name(r.id) + " " + outcome + (r.reason.empty() ? "" : ": " + r.reason);
                }
            }
            if (now != JobState::starting) started_on_clear_ = 0;
        }

        if (queued && r.state == JobState::starting) starting_.insert(r.id);
        if (queued && r.state == JobState::planned) {
            if (was_starting) {
                starting_.erase(r.id);
                // Its start was refused (nothing moved): it keeps its place; a start the queue
                // made waits for the operator rather than being tried again and again.
                if (queue_started_ == r.id) {
                    state_.paused = true;
                    state_.paused_reason = job_name(r.id) + " could not start: " + r.reason;
                    touched = true;
                }
            } else {
                may_start_next = true;  // its plan is ready
            }
        }
        if (queued && !queueable(r.state) && r.state != JobState::starting) {
            state_.jobs.erase(at);
            starting_.erase(r.id);
            spdlog::info("queue.left {}: {}", job_name(r.id), to_string(r.state));
            touched = true;
            may_start_next = true;  // the next may be due (it left without printing)
        }
        if (queue_started_ == r.id && r.state != JobState::starting) queue_started_ = 0;
        if (touched)
            changed();
        else if (queued)
            publish();  // a queued job's state shows in the queue (planned now)
    }
    if (may_start_next) start_next_if_due();
}

void QueueComponent::start_next_if_due() {
    if (config_.auto_start != AutoStart::after_clear) return;
    // One at a time: two callers (a job planned, the operator's clear) must not both start the
    // next job, nor the second take the store's refusal for a reason to pause.
    std::lock_guard one(start_mu_);
    jobs::JobStore& store = jobs_.store();
    std::int64_t next = 0;
    {
        std::lock_guard lock(mu_);
        drop_gone_jobs();
        if (!state_.bed.clear || state_.paused || state_.jobs.empty()) return;
        next = state_.jobs.front();
        if (starting_.contains(next)) return;
        try {
            if (store.get(next).state != JobState::planned) return;  // it starts once planned
        } catch (const jobs::JobNotFound&) {
            return;
        }
        for (const JobRecord& r : store.list())
            if (jobs::holds_cell(r.state)) return;  // it starts after that one, and a clear
        queue_started_ = next;
    }
    try {
        printer_.start_print(next, "queue");  // after_clear: the queue's own start
        spdlog::info("queue.started {}", job_name(next));
    } catch (const std::exception& e) {
        std::lock_guard lock(mu_);
        // Started meanwhile by someone else (the operator, a submit with start): not a refusal.
        try {
            if (store.get(next).state != JobState::planned) return;
        } catch (const jobs::JobNotFound&) {
            return;
        }
        for (const JobRecord& r : store.list())
            if (jobs::holds_cell(r.state)) return;
        state_.paused = true;
        state_.paused_reason = job_name(next) + " could not start: " + e.what();
        spdlog::warn("queue.paused {}", state_.paused_reason);
        changed();
    }
}

json QueueComponent::view() const {
    json v = to_json(state_);
    v["auto_start"] = to_string(config_.auto_start);
    json list = json::array();
    for (std::size_t i = 0; i < state_.jobs.size(); ++i) {
        json e = {{"position", i + 1}, {"id", state_.jobs[i]}};
        try {
            const JobRecord r = jobs_.store().get(state_.jobs[i]);
            e["name"] = r.name;
            e["state"] = std::string(to_string(r.state));
        } catch (const jobs::JobNotFound&) {
            e["state"] = "removed";
        }
        list.push_back(std::move(e));
    }
    v["jobs"] = std::move(list);
    if (!state_.bed.clear && state_.bed.job > 0) {
        try {
            v["bed"]["name"] = jobs_.store().get(state_.bed.job).name;
        } catch (const jobs::JobNotFound&) {
        }
    }
    return v;
}

void QueueComponent::commit(const QueueState& before) {
    try {
        save_queue_state(file_, state_);
    } catch (const std::exception& e) {
        state_ = before;
        throw ApiError::unavailable(std::string("unavailable: the queue could not be saved (") +
                                    e.what() + "): nothing changed");
    }
    publish();
}

void QueueComponent::changed() {
    try {
        save_queue_state(file_, state_);
    } catch (const std::exception& e) {
        spdlog::error("queue.not_saved {}: the queue holds in memory; the next change tries again",
                      e.what());
    }
    publish();
}

void QueueComponent::publish() const {
    endpoints_.publish({.topic = api::topic::queue,
                        .method = api::notify::queue,
                        .params = view(),
                        .delivery = api::Delivery::every});
}

}  // namespace fibrecell::daemon::queue
