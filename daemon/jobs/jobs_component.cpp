#include "daemon/jobs/jobs_component.hpp"

#include "config/base64.hpp"
#include "daemon/api/params.hpp"
#include "daemon/jobs/job_api.hpp"
#include "daemon/jobs/planned_use.hpp"
#include "daemon/jobs/plan_runner.hpp"
#include "daemon/jobs/thread_pool.hpp"
#include "daemon/print/print_settings.hpp"

#include <spdlog/spdlog.h>

#include <charconv>
#include <fstream>

namespace fibrecell::daemon::jobs {

using api::ApiError;
using api::CallContext;
using api::ParamReader;
using nlohmann::json;

namespace {

// What the plan directory's report.json says about the job, for people (jobs, status, watch).
json plan_summary(const json& report) {
    if (!report.is_object() || !report.contains("layers")) return nullptr;
    json s = json::object();
    const json& layers = report["layers"];
    s["layers"] = layers.value("pla", 0) + layers.value("ccf", 0);
    if (report.contains("fibre")) s["fibre_length_m"] = report["fibre"].value("length_m", 0.0);
    if (report.contains("pla")) s["pla_length_m"] = report["pla"].value("length_m", 0.0);
    if (report.contains("robot")) {
        const json& r = report["robot"];
        s["modules"] = r.value("modules", 0);
        s["events"] = r.value("events", 0);
        s["duration_s"] = r.value("duration_s", 0.0);
    }
    if (report.contains("mechanics")) {  // the predicted stiffness (docs/mechanics.md)
        const json& m = report["mechanics"];
        s["stiffness_n_per_mm"] = m["reinforced"].value("stiffness_n_per_mm", 0.0);
        s["stiffness_gain"] = m.value("stiffness_gain", 0.0);
    }
    return s;
}

JobInput submitted_job(const json& params, const CallContext& ctx) {
    ParamReader p(ctx.method, params);
    JobInput input;
    input.job_yaml = p.string("job_yaml");
    input.start_when_planned = p.boolean_or("start", false);
    input.submitted_by = ctx.user;
    if (p.has("files")) {
        const json& files = p.object("files");
        for (const auto& [name, data] : files.items()) {
            if (!data.is_string()) p.fail("files", name + " is not a base64 string");
            try {
                input.files.emplace_back(name, config::base64_decode(data.get<std::string>()));
            } catch (const std::invalid_argument& e) {
                p.fail("files", name + ": " + e.what());
            }
        }
    }
    p.finish();
    return input;
}

}  // namespace

JobsComponent::JobsComponent(const CellConfig& cell, const JobsConfig& config)
    : cell_(cell), config_(config) {}

JobsComponent::~JobsComponent() = default;

void JobsComponent::add_job_view(JobView view) { views_.push_back(std::move(view)); }

void JobsComponent::on_planned(Planned planned) { planned_.push_back(std::move(planned)); }

void JobsComponent::on_change(Changed changed) { changed_.push_back(std::move(changed)); }

void JobsComponent::register_endpoints(component::Endpoints& endpoints) {
    endpoints.method("job.submit", [this](const json& params, const CallContext& ctx) {
        const JobInput input = submitted_job(params, ctx);
        JobRecord r;
        try {
            r = as_api([&] { return store_->submit(input); });
        } catch (const JobInputError& e) {
            throw ApiError::invalid_params(e.what());
        } catch (const config::ConfigError& e) {
            throw ApiError::invalid_params(e.what());
        } catch (const print::SettingsError& e) {
            throw ApiError::invalid_params(e.what());
        }
        planner_->enqueue(r.id);
        spdlog::info("job.submitted {} ({}) by {}", r.id, r.name, ctx.peer);
        return job_json(r);
    });

    endpoints.method("job.list", [this](const json& params, const CallContext& ctx) {
        ParamReader(ctx.method, params).finish();
        json out = json::array();
        for (const JobRecord& r : store_->list()) out.push_back(job_json(r));
        return out;
    });

    endpoints.control_method("job.get", [this](const json& params, const CallContext& ctx) {
        const std::int64_t id = job_id_param(params, ctx);
        return job_json(as_api([&] { return store_->get(id); }));
    });

    // A new plan for a planned job (the cell changed since, docs/jobs.md) or a failed plan.
    endpoints.method("job.replan", [this](const json& params, const CallContext& ctx) {
        const std::int64_t id = job_id_param(params, ctx);
        const JobRecord r = as_api([&] { return store_->request(id, JobAction::replan); });
        planner_->enqueue(id);
        spdlog::info("job.replan {} by {}", id, ctx.peer);
        return job_json(r);
    });

    endpoints.method("job.remove", [this](const json& params, const CallContext& ctx) {
        const std::int64_t id = job_id_param(params, ctx);
        const JobRecord r = as_api([&] { return store_->request(id, JobAction::remove); });
        // Its watchers (another dashboard) hear that it is gone; the store has no record left.
        endpoints_.publish({.topic = std::to_string(r.id),
                            .method = api::notify::job_state,
                            .params = {{"id", r.id}, {"name", r.name}, {"state", "removed"}},
                            .delivery = api::Delivery::every});
        return json{{"removed", r.id}};
    });

    endpoints.event(api::notify::job_state);
    endpoints.event(api::notify::job_progress);

    // A job's plan files (the layer previews, report.json, toolpaths.json) for its pages.
    endpoints.file_route("/api/jobs/", [this](std::string_view key) -> std::optional<std::filesystem::path> {
        std::int64_t id = 0;
        const auto [end, ec] = std::from_chars(key.data(), key.data() + key.size(), id);
        if (ec != std::errc() || end != key.data() + key.size() || id <= 0) return std::nullopt;
        return store_->plan_dir(id);
    });
    endpoints_ = endpoints;
}

void JobsComponent::start() {
    store_ = std::make_unique<JobStore>(JobStoreOptions{
        .state_dir = cell_.state_dir,
        .max_queued = config_.max_queued,
        .keep_completed = config_.keep_completed,
        .plan_retries = config_.plan_retries,
        // A setting this cell cannot print refuses the submit at once; the settings made here are
        // the plan's.
        .settings_for = [cell = cell_](const planner::JobSpec& job) { return print::print_settings(job, cell); }});
    const LoadReport loaded = store_->load_all();
    for (const auto& w : loaded.warnings) spdlog::warn("jobs.load {}", w);
    spdlog::info("jobs.loaded {} jobs ({} to plan, {} interrupted, {} failed)", loaded.loaded.size(),
                 loaded.to_plan.size(), loaded.interrupted.size(), loaded.failed.size());
    to_plan_ = loaded.to_plan;
    store_->on_change([this](const JobRecord& r) {
        publish_job(r);
        for (const Changed& f : changed_) f(r);
    });

    planning_pool_ = std::make_unique<ThreadPool>(
        ThreadPoolOptions{.threads = config_.planner_threads, .nice = config_.planner_nice});
    planner_ = std::make_unique<PlanRunner>(
        *store_, PlanRunnerOptions{.workers = config_.planning_workers,
                                   .planner_nice = config_.planner_nice,
                                   .cell = cell_,
                                   .executor = planning_pool_.get()});
    planner_->on_progress([this](std::int64_t id, const JobProgress& p) {
        endpoints_.publish({.topic = std::to_string(id),
                            .method = api::notify::job_progress,
                            .params = {{"job", id},
                                       {"state", "planning"},
                                       {"planning", {{"stage", p.stage}, {"fraction", p.fraction}}}},
                            .delivery = api::Delivery::latest});
    });
    planner_->on_finished([this](const JobRecord& r) {
        for (const Planned& f : planned_) f(r);
    });
}

void JobsComponent::serve() {
    for (const std::int64_t id : to_plan_) planner_->enqueue(id);
    to_plan_.clear();
}

void JobsComponent::stop() {
    if (planner_) planner_->cancel_all();
}

bool JobsComponent::join(Deadline deadline) {
    if (!planner_) return true;
    const std::string planning = planner_->running_summary();
    const auto grace = std::chrono::duration_cast<std::chrono::milliseconds>(
        std::max(deadline - std::chrono::steady_clock::now(), Deadline::duration::zero()));
    if (planner_->join(grace)) return true;
    spdlog::warn("service.stop_unfinished planning of {} did not reach a cancel check within {} s "
                 "(jobs.stop_grace_s): not waiting for it; it plans again at the next start",
                 planning, config_.stop_grace_s);
    return false;
}

JobRecord JobsComponent::abort_planning(std::int64_t id) { return planner_->abort(id); }

void JobsComponent::view_changed(std::int64_t id) {
    try {
        publish_job(store_->get(id));
    } catch (const JobNotFound&) {
        // Removed meanwhile: its watchers heard so.
    }
}

json JobsComponent::job_json(const JobRecord& r) const {
    json j = {{"id", r.id},
              {"name", r.name},
              {"state", std::string(to_string(r.state))},
              {"submitted_at", r.submitted_at},
              {"updated_at", r.updated_at},
              {"last_confirmed_event", r.last_confirmed_event},
              {"dir", store_->job_dir(r.id).string()}};
    if (!r.reason.empty()) j["reason"] = r.reason;
    for (const auto& [key, value] : {std::pair{"submitted_by", &r.submitted_by},
                                     {"started_by", &r.started_by}, {"planned_at", &r.planned_at},
                                     {"started_at", &r.started_at}, {"ended_at", &r.ended_at}})
        if (!value->empty()) j[key] = *value;
    if (r.state == JobState::planning)
        j["planning"] = {{"stage", r.progress.stage.empty() ? "queued" : r.progress.stage},
                         {"fraction", r.progress.fraction}};
    if (r.state != JobState::planning && r.state != JobState::failed) {
        const json plan = plan_summary(read_json_file(store_->plan_dir(r.id) / "report.json"));
        if (!plan.is_null()) j["plan"] = plan;
    }
    for (const JobView& view : views_) view(r, j);
    const json result = read_json_file(store_->job_dir(r.id) / "result.json");
    if (!result.is_null()) j["result"] = result;
    return j;
}

void JobsComponent::publish_job(const JobRecord& r) {
    endpoints_.publish({.topic = std::to_string(r.id),
                        .method = api::notify::job_state,
                        .params = job_json(r),
                        .delivery = api::Delivery::every});
}

}  // namespace fibrecell::daemon::jobs
