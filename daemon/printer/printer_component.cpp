#include "daemon/printer/printer_component.hpp"

#include "daemon/api/api_error.hpp"
#include "daemon/api/params.hpp"
#include "daemon/jobs/job_api.hpp"

#include <spdlog/spdlog.h>

namespace fibrecell::daemon::printer {

using api::ApiError;
using api::CallContext;
using jobs::as_api;
using jobs::JobAction;
using jobs::JobRecord;
using jobs::JobState;
using nlohmann::json;

PrinterComponent::PrinterComponent(jobs::JobsComponent& jobs, devices::CellComponent& cell,
                                   const CellConfig& config, PrintRunnerOptions options)
    : jobs_(jobs), cell_(cell), config_(config), options_(options) {
    jobs_.add_job_view([this](const JobRecord& r, json& view) {
        if (r.state == JobState::planned) {
            std::lock_guard lock(refused_mu_);
            if (const auto it = start_refused_.find(r.id); it != start_refused_.end())
                view["start_refused"] = it->second;
        }
        if (!runner_ || runner_->current_job() != r.id) return;
        const json s = runner_->print_status();
        if (s.contains("progress")) {
            view["print"] = s["progress"];
            view["last_confirmed_event"] = s["progress"]["event"];
        }
    });
    jobs_.on_planned([this](const JobRecord& r) { start_when_planned(r); });
    cell_.add_status_part([this](json& status) {
        status["heaters"] = runner_->heater_status();
        const json print = runner_->print_status();
        if (print.contains("job")) {
            status["job"] = print["job"];
            status["progress"] = print["progress"];
            status["sync"] = print["sync"];
        } else {
            status["job"] = nullptr;
        }
    });
    cell_.on_estop([this] { runner_->abort_for_estop(); });
}

PrinterComponent::~PrinterComponent() = default;

void PrinterComponent::add_start_gate(StartGate gate) { gates_.push_back(std::move(gate)); }

void PrinterComponent::on_print_finished(std::function<void(std::int64_t)> f) {
    finished_.push_back(std::move(f));
}

void PrinterComponent::on_feed(PrintRunner::FeedObserver f) { feed_.push_back(std::move(f)); }

std::optional<std::string> PrinterComponent::held_at_gate(const JobRecord& r) const {
    for (const StartGate& gate : gates_)
        if (auto reason = gate(r)) return reason;
    return std::nullopt;
}

void PrinterComponent::register_endpoints(component::Endpoints& endpoints) {
    endpoints.method("job.start", [this](const json& params, const CallContext& ctx) {
        return jobs_.job_json(start_print(jobs::job_id_param(params, ctx), ctx.user));
    });

    endpoints.control_method("job.pause", [this](const json& params, const CallContext& ctx) {
        const std::int64_t id = job_or_on_cell(params, ctx);
        const JobRecord r = as_api([&] { return jobs_.store().request(id, JobAction::pause); });
        runner_->pause(id, nullptr);
        return jobs_.job_json(r);
    });

    endpoints.method("job.resume", [this](const json& params, const CallContext& ctx) {
        // journal_lost: true is the operator's word for a job whose journal is gone.
        json rest = params;
        bool journal_lost = false;
        if (rest.is_object() && rest.contains("journal_lost")) {
            journal_lost = api::ParamReader(ctx.method, params).boolean_or("journal_lost", false);
            rest.erase("journal_lost");
        }
        const std::int64_t id = job_or_on_cell(rest, ctx);
        std::unique_lock one(start_mu_);
        const JobRecord before = as_api([&] { return jobs_.store().get(id); });
        // Re-entry after an interruption is a new start: the gates have their say.
        if (before.state == JobState::interrupted)
            if (const auto reason = held_at_gate(before))
                throw ApiError::conflict("job " + std::to_string(id) + " cannot start: " + *reason);
        if (journal_lost) as_api([&] { jobs_.store().accept_lost_journal(id); });
        const JobRecord r =
            as_api([&] { return jobs_.store().request(id, JobAction::resume, ctx.user); });
        one.unlock();
        if (before.state == JobState::interrupted)
            runner_->start(id, nullptr);  // re-entry: a new run from the resume point
        else
            runner_->resume(id, nullptr);
        return jobs_.job_json(r);
    });

    endpoints.control_method("job.abort", [this](const json& params, const CallContext& ctx) {
        const std::int64_t id = job_or_on_cell(params, ctx);
        const JobState before = as_api([&] { return jobs_.store().get(id); }).state;
        const JobRecord r = as_api([&] {
            return before == JobState::planning ? jobs_.abort_planning(id)
                                                : jobs_.store().request(id, JobAction::abort);
        });
        if (jobs::holds_cell(before)) runner_->abort(id, nullptr);
        return jobs_.job_json(r);
    });

    endpoints.event(api::notify::job_progress);
    endpoints_ = endpoints;
}

void PrinterComponent::start() {
    runner_ = std::make_unique<PrintRunner>(jobs_.store(), cell_.devices(), config_, options_);
    runner_->on_finished([this](std::int64_t id) {
        for (const auto& f : finished_) f(id);
    });
    runner_->on_feed([this](const PrintRunner::Feed& feed) {
        for (const auto& f : feed_) f(feed);
    });
    runner_->on_progress([this](std::int64_t id, const json& progress) {
        endpoints_.publish({.topic = std::to_string(id),
                            .method = api::notify::job_progress,
                            .params = {{"job", id}, {"state", "printing"}, {"print", progress}},
                            .delivery = api::Delivery::latest});
    });
}

void PrinterComponent::stop() {
    if (runner_) runner_->stop();
}

JobRecord PrinterComponent::start_print(std::int64_t id, const std::string& by) {
    // The gates' answer and the start at once: a gate's ground (a clear bed) cannot change
    // between them.
    std::lock_guard one(start_mu_);
    if (const auto reason = held_at_gate(as_api([&] { return jobs_.store().get(id); })))
        throw ApiError::conflict("job " + std::to_string(id) + " cannot start: " + *reason);
    const JobRecord r = as_api([&] { return jobs_.store().request(id, JobAction::start, by); });
    runner_->start(id, nullptr);
    std::lock_guard lock(refused_mu_);
    start_refused_.erase(id);
    return r;
}

void PrinterComponent::start_when_planned(const JobRecord& r) {
    if (r.state != JobState::planned || !r.start_when_planned) return;
    try {
        // Started already (by the queue, or by hand, since its plan was done): nothing to do.
        if (jobs_.store().get(r.id).state != JobState::planned) return;
        start_print(r.id, r.submitted_by);  // the submitter asked for the start
    } catch (const std::exception& e) {
        {
            std::lock_guard lock(refused_mu_);
            start_refused_[r.id] = e.what();
        }
        spdlog::warn("job {} planned; not started: {}", r.id, e.what());
        jobs_.view_changed(r.id);
    }
}

std::int64_t PrinterComponent::job_or_on_cell(const json& params, const CallContext& ctx) const {
    if (api::ParamReader(ctx.method, params).has("job")) return jobs::job_id_param(params, ctx);
    if (const auto current = runner_->current_job()) return *current;
    for (const JobRecord& r : jobs_.store().list())
        if (jobs::holds_cell(r.state)) return r.id;
    throw ApiError::conflict(ctx.method + ": no job is on the cell; name one");
}

std::string PrinterComponent::one_line_status() const {
    const auto job = runner_ ? runner_->current_job() : std::nullopt;
    if (!job) return "idle, " + std::to_string(runner_ ? jobs_.store().list().size() : 0) + " jobs";
    const json s = runner_->print_status();
    const json& p = s.value("progress", json::object());
    return "printing job " + std::to_string(*job) + ", layer " +
           std::to_string(p.value("layer", 0)) + "/" + std::to_string(p.value("layers", 0));
}

}  // namespace fibrecell::daemon::printer
