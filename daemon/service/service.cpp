#include "daemon/service/service.hpp"

#include "config/base64.hpp"
#include "config/logging.hpp"
#include "config/thread_priority.hpp"
#include "daemon/api/api_error.hpp"
#include "daemon/api/params.hpp"
#include "daemon/print/print_settings.hpp"
#include "daemon/service/log_feed.hpp"

#include <spdlog/spdlog.h>

#include <unistd.h>

#include <charconv>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace fibrecell::daemon::service {

using api::ApiError;
using api::CallContext;
using api::ParamReader;
using jobs::JobAction;
using jobs::JobRecord;
using jobs::JobState;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

PrintRunnerOptions load_print_options(config::Section s) {
    PrintRunnerOptions o;
    using ms = std::chrono::milliseconds;
    o.connect_timeout = ms(static_cast<long>(1000 * s.number("connect_timeout_s", 10, 0.1, 600)));
    o.heartbeat_timeout =
        ms(static_cast<long>(1000 * s.number("heartbeat_timeout_s", 1, 0.2, 60)));
    const auto minutes = [&](const char* key, double fallback, double low) {
        return ms(static_cast<long>(60000 * s.number(key, fallback, low, 24 * 60)));
    };
    o.heaters.paused_timeout = minutes("heater_timeout_min", 30, 0.01);
    o.heaters.hold_after_print = minutes("heater_hold_min", 0, 0);
    o.heaters.idle_timeout = minutes("idle_heater_timeout_min", 10, 0.01);
    o.realtime_priority = s.integer("realtime_priority", 20, 0, 99);
    o.late_cut_mm = s.number("late_cut_mm", o.late_cut_mm, 0, 1000, true);
    s.finish();
    return o;
}

json read_json_file(const std::filesystem::path& p) {
    std::ifstream in(p);
    if (!in) return nullptr;
    try {
        return json::parse(in);
    } catch (const json::exception&) {
        return nullptr;
    }
}

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

// Maps the job store's refusals to API errors; anything else is the caller's business.
template <class F>
auto as_api(F&& f) -> decltype(f()) {
    try {
        return f();
    } catch (const jobs::JobNotFound& e) {
        throw ApiError::not_found(e.what());
    } catch (const jobs::JobConflict& e) {
        throw ApiError::conflict(e.what());
    } catch (const jobs::StateWriteError& e) {
        throw ApiError::unavailable(std::string("unavailable: ") + e.what());  // a full disk
    } catch (const std::system_error& e) {
        // A job's files that could not be written (a full disk, an I/O error): nothing was
        // stored, and another try may succeed once there is room.
        throw ApiError::unavailable(std::string("unavailable: not stored: ") + e.what());
    }
}

}  // namespace

ServiceConfig load_service_config(const std::string& path) {
    ServiceConfig c;
    c.cell = load_cell_config(path, [&](config::Section& root) {
        c.api = api::load_api_config(root.section("api"));
        c.jobs = jobs::load_jobs_config(root.section("jobs"));
        c.print = load_print_options(root.section("print"));
    });
    return c;
}

Service::Service(boost::asio::io_context& io, ServiceConfig config)
    : io_(io), config_(std::move(config)), ticker_(io) {}

Service::~Service() { stop(); }

void Service::start() {
    // The state directory is this service's alone: private, and locked against a second one.
    config::ensure_private_directory(config_.cell.state_dir, "state directory");
    if (!state_lock_)
        state_lock_ = std::make_unique<config::DirectoryLock>(
            config_.cell.state_dir, "fibrecelld pid " + std::to_string(::getpid()) +
                                        " (socket " + config_.api.socket_path + ")");
    store_ = std::make_unique<jobs::JobStore>(jobs::JobStoreOptions{
        .state_dir = config_.cell.state_dir,
        .max_queued = config_.jobs.max_queued,
        .keep_completed = config_.jobs.keep_completed,
        .plan_retries = config_.jobs.plan_retries,
        // A setting this cell cannot print refuses the submit at once.
        .check_job = [cell = config_.cell](const planner::JobSpec& job) {
            print::print_settings(job, cell);
        }});
    const jobs::LoadReport loaded = store_->load_all();
    for (const auto& w : loaded.warnings) spdlog::warn("jobs.load {}", w);
    spdlog::info("jobs.loaded {} jobs ({} to plan, {} interrupted, {} failed)", loaded.loaded.size(),
                 loaded.to_plan.size(), loaded.interrupted.size(), loaded.failed.size());
    store_->on_change([this](const JobRecord& r) { publish_job(r); });

    api_ = std::make_unique<api::ApiServer>(io_, config_.api);
    register_methods();
    api_->start();
    if (config_.api.http.enabled) start_dashboard();
    feed_log_to([api = api_.get()](json line) {
        api->publish({.topic = api::topic::log,
                      .method = api::notify::log,
                      .params = std::move(line),
                      .delivery = api::Delivery::every});
    });

    // Before the devices start their threads (config/thread_priority.hpp).
    config::set_time_critical_priority(config_.print.realtime_priority);
    devices_ = std::make_unique<CellDevices>(config_.cell);
    printer_ = std::make_unique<PrintRunner>(*store_, *devices_, config_.cell, config_.print);
    printer_->on_progress([this](std::int64_t id, const json& progress) {
        api_->publish({.topic = std::to_string(id),
                       .method = api::notify::job_progress,
                       .params = {{"job", id}, {"state", "printing"}, {"print", progress}},
                       .delivery = api::Delivery::latest});
    });

    planning_pool_ = std::make_unique<jobs::ThreadPool>(jobs::ThreadPoolOptions{
        .threads = config_.jobs.planner_threads, .nice = config_.jobs.planner_nice});
    planner_ = std::make_unique<jobs::PlanRunner>(
        *store_, jobs::PlanRunnerOptions{.workers = config_.jobs.planning_workers,
                                         .planner_nice = config_.jobs.planner_nice,
                                         .cell = config_.cell,
                                         .executor = planning_pool_.get()});
    planner_->on_progress([this](std::int64_t id, const jobs::JobProgress& p) {
        api_->publish({.topic = std::to_string(id),
                       .method = api::notify::job_progress,
                       .params = {{"job", id},
                                  {"state", "planning"},
                                  {"planning", {{"stage", p.stage}, {"fraction", p.fraction}}}},
                       .delivery = api::Delivery::latest});
    });
    planner_->on_finished([this](const JobRecord& r) {
        if (r.state == JobState::planned && r.start_when_planned) {
            try {
                store_->request(r.id, JobAction::start);
                printer_->start(r.id, nullptr);
            } catch (const std::exception& e) {
                spdlog::warn("job {} planned; not started: {}", r.id, e.what());
            }
        }
    });
    for (const std::int64_t id : loaded.to_plan) planner_->enqueue(id);

    try {
        devices_->connect(config_.print.connect_timeout);
        spdlog::info("cell.connected {}", config_.cell.name);
    } catch (const std::exception& e) {
        spdlog::warn("cell.not_connected {} (a start retries)", e.what());
    }
    tick();
}

void Service::start_dashboard() {
    http_ = std::make_unique<http::HttpServer>(io_, config_.api, *api_);
    // A job's plan files (the layer previews, report.json, toolpaths.json) for its pages.
    http_->add_file_route("/api/jobs/", [this](std::string_view key) -> std::optional<fs::path> {
        std::int64_t id = 0;
        const auto [end, ec] = std::from_chars(key.data(), key.data() + key.size(), id);
        if (ec != std::errc() || end != key.data() + key.size() || id <= 0) return std::nullopt;
        return store_->plan_dir(id);
    });
    try {
        http_->start();
    } catch (...) {
        api_->stop();
        throw;
    }
}

std::string Service::reload(const ServiceConfig& next) {
    std::vector<std::string> ignored;
    if (next.cell.simulated != config_.cell.simulated) ignored.push_back("simulated");
    if (next.cell.state_dir != config_.cell.state_dir) ignored.push_back("state_dir");
    if (next.api.socket_path != config_.api.socket_path || next.api.tcp.enabled != config_.api.tcp.enabled ||
        next.api.tcp.port != config_.api.tcp.port || next.api.tcp.host != config_.api.tcp.host)
        ignored.push_back("api listeners");
    config::setup_logging(next.cell.log_level);
    api_->update_limits(next.api);
    if (http_) http_->update(next.api);
    if (next.api.http.enabled != config_.api.http.enabled || next.api.http.port != config_.api.http.port ||
        next.api.http.host != config_.api.http.host)
        ignored.push_back("api.http listener");
    config_.api = next.api;
    config_.cell.log_level = next.cell.log_level;
    std::string what = "applied log_level, api limits and token";
    if (!ignored.empty()) {
        what += "; needs a restart: ";
        for (std::size_t i = 0; i < ignored.size(); ++i) what += (i ? ", " : "") + ignored[i];
    }
    return what;
}

bool Service::stop() {
    if (stopping_ || !store_) return true;
    stopping_ = true;
    feed_log_to(nullptr);
    ticker_.cancel();
    if (http_) http_->stop();
    if (api_) api_->stop();
    if (planner_) planner_->cancel_all();
    if (printer_) printer_->stop();
    if (devices_) devices_->disconnect();
    const auto grace = std::chrono::duration_cast<std::chrono::milliseconds>(
        std::chrono::duration<double>(config_.jobs.stop_grace_s));
    const std::string planning = planner_ ? planner_->running_summary() : "";
    if (planner_ && !planner_->join(grace)) {
        spdlog::warn("service.stop_unfinished planning of {} did not reach a cancel check within "
                     "{} s (jobs.stop_grace_s): not waiting for it; it plans again at the next start",
                     planning, config_.jobs.stop_grace_s);
        return false;
    }
    spdlog::info("service.stopped");
    return true;
}

void Service::tick() {
    ticker_.expires_after(std::chrono::milliseconds(500));
    ticker_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || stopping_) return;
        // The robot's heartbeat proves this loop runs, not just the link's thread.
        devices_->robot_io().service_alive();
        api_->publish({.topic = api::topic::cell,
                       .method = api::notify::cell_status,
                       .params = cell_status(),
                       .delivery = api::Delivery::latest});
        if (status_line_) status_line_(one_line_status());
        tick();
    });
}

std::string Service::one_line_status() const {
    const auto job = printer_ ? printer_->current_job() : std::nullopt;
    if (!job) return "idle, " + std::to_string(store_ ? store_->list().size() : 0) + " jobs";
    const json s = printer_->print_status();
    const json& p = s.value("progress", json::object());
    return "printing job " + std::to_string(*job) + ", layer " +
           std::to_string(p.value("layer", 0)) + "/" + std::to_string(p.value("layers", 0));
}

json Service::job_json(const JobRecord& r) const {
    json j = {{"id", r.id},
              {"name", r.name},
              {"state", std::string(jobs::to_string(r.state))},
              {"submitted_at", r.submitted_at},
              {"updated_at", r.updated_at},
              {"last_confirmed_event", r.last_confirmed_event},
              {"dir", store_->job_dir(r.id).string()}};
    if (!r.reason.empty()) j["reason"] = r.reason;
    if (r.state == JobState::planning)
        j["planning"] = {{"stage", r.progress.stage.empty() ? "queued" : r.progress.stage},
                         {"fraction", r.progress.fraction}};
    if (r.state != JobState::planning && r.state != JobState::failed) {
        const json plan = plan_summary(read_json_file(store_->plan_dir(r.id) / "report.json"));
        if (!plan.is_null()) j["plan"] = plan;
    }
    if (printer_ && printer_->current_job() == r.id) {
        const json s = printer_->print_status();
        if (s.contains("progress")) {
            j["print"] = s["progress"];
            j["last_confirmed_event"] = s["progress"]["event"];
        }
    }
    const json result = read_json_file(store_->job_dir(r.id) / "result.json");
    if (!result.is_null()) j["result"] = result;
    return j;
}

json Service::cell_status() const {
    json s = devices_->status();
    s["name"] = config_.cell.name;
    s["simulated"] = devices_->simulated();
    s["time_scale"] = devices_->time_scale();
    s["heaters"] = printer_->heater_status();
    const json print = printer_->print_status();
    if (print.contains("job")) {
        s["job"] = print["job"];
        s["progress"] = print["progress"];
        s["sync"] = print["sync"];
    } else {
        s["job"] = nullptr;
    }
    return s;
}

void Service::publish_job(const JobRecord& r) {
    api_->publish({.topic = std::to_string(r.id),
                   .method = api::notify::job_state,
                   .params = job_json(r),
                   .delivery = api::Delivery::every});
}

std::int64_t Service::job_param(const json& params, const CallContext& ctx,
                                bool default_to_current) const {
    ParamReader p(ctx.method, params);
    if (!p.has("job")) {
        if (default_to_current) {
            if (const auto current = printer_->current_job()) return *current;
            for (const JobRecord& r : store_->list())
                if (jobs::holds_cell(r.state)) return r.id;
            throw ApiError::conflict(ctx.method + ": no job is on the cell; name one");
        }
        p.fail("job", "is required (a job id)");
    }
    const std::int64_t id = p.integer_or("job", 0, 1, std::numeric_limits<std::int64_t>::max());
    p.finish();
    return id;
}

void Service::register_methods() {
    api_->add_method("server.info", [this](const json&, const CallContext&) {
        return json{{"service", "fibrecelld"},
                    {"version", FIBRECELL_VERSION},
                    {"cell", config_.cell.name},
                    {"simulated", config_.cell.simulated},
                    {"pid", static_cast<long>(::getpid())},
                    {"tcp_port", api_->tcp_port()},
                    {"http_port", http_ ? http_->port() : 0},
                    {"state_dir", config_.cell.state_dir}};
    });

    api_->add_method("job.submit", [this](const json& params, const CallContext& ctx) {
        ParamReader p(ctx.method, params);
        jobs::JobInput input;
        input.job_yaml = p.string("job_yaml");
        input.start_when_planned = p.boolean_or("start", false);
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
        JobRecord r;
        try {
            r = as_api([&] { return store_->submit(input); });
        } catch (const jobs::JobInputError& e) {
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

    api_->add_method("job.list", [this](const json& params, const CallContext& ctx) {
        ParamReader(ctx.method, params).finish();
        json out = json::array();
        for (const JobRecord& r : store_->list()) out.push_back(job_json(r));
        return out;
    });

    api_->add_method("job.get", [this](const json& params, const CallContext& ctx) {
        const std::int64_t id = job_param(params, ctx, false);
        return job_json(as_api([&] { return store_->get(id); }));
    });

    api_->add_method("job.start", [this](const json& params, const CallContext& ctx) {
        const std::int64_t id = job_param(params, ctx, false);
        const JobRecord r = as_api([&] { return store_->request(id, JobAction::start); });
        printer_->start(id, nullptr);
        return job_json(r);
    });

    api_->add_method("job.pause", [this](const json& params, const CallContext& ctx) {
        const std::int64_t id = job_param(params, ctx, true);
        const JobRecord r = as_api([&] { return store_->request(id, JobAction::pause); });
        printer_->pause(id, nullptr);
        return job_json(r);
    });

    api_->add_method("job.resume", [this](const json& params, const CallContext& ctx) {
        // journal_lost: true is the operator's word for a job whose journal is gone.
        json rest = params;
        bool journal_lost = false;
        if (rest.is_object() && rest.contains("journal_lost")) {
            journal_lost = ParamReader(ctx.method, params).boolean_or("journal_lost", false);
            rest.erase("journal_lost");
        }
        const std::int64_t id = job_param(rest, ctx, true);
        if (journal_lost) as_api([&] { store_->accept_lost_journal(id); });
        const JobState before = as_api([&] { return store_->get(id); }).state;
        const JobRecord r = as_api([&] { return store_->request(id, JobAction::resume); });
        if (before == JobState::interrupted)
            printer_->start(id, nullptr);  // re-entry: a new run from the resume point
        else
            printer_->resume(id, nullptr);
        return job_json(r);
    });

    api_->add_method("job.abort", [this](const json& params, const CallContext& ctx) {
        const std::int64_t id = job_param(params, ctx, true);
        const JobState before = as_api([&] { return store_->get(id); }).state;
        const JobRecord r = as_api([&] {
            return before == JobState::planning ? planner_->abort(id)
                                                : store_->request(id, JobAction::abort);
        });
        if (jobs::holds_cell(before)) printer_->abort(id, nullptr);
        return job_json(r);
    });

    // A new plan for a planned job (the cell changed since, docs/jobs.md) or a failed plan.
    api_->add_method("job.replan", [this](const json& params, const CallContext& ctx) {
        const std::int64_t id = job_param(params, ctx, false);
        const JobRecord r = as_api([&] { return store_->request(id, JobAction::replan); });
        planner_->enqueue(id);
        spdlog::info("job.replan {} by {}", id, ctx.peer);
        return job_json(r);
    });

    api_->add_method("job.remove", [this](const json& params, const CallContext& ctx) {
        const std::int64_t id = job_param(params, ctx, false);
        const JobRecord r = as_api([&] { return store_->request(id, JobAction::remove); });
        // Its watchers (another dashboard) hear that it is gone; the store has no record left.
        api_->publish({.topic = std::to_string(r.id),
                       .method = api::notify::job_state,
                       .params = {{"id", r.id}, {"name", r.name}, {"state", "removed"}},
                       .delivery = api::Delivery::every});
        return json{{"removed", r.id}};
    });

    api_->add_method("cell.status", [this](const json& params, const CallContext& ctx) {
        ParamReader(ctx.method, params).finish();
        return cell_status();
    });

    api_->add_method("cell.estop", [this](const json& params, const CallContext& ctx) {
        ParamReader(ctx.method, params).finish();
        spdlog::critical("cell.estop requested by {}", ctx.peer);
        printer_->estop();
        std::string note = "M112 sent and robot abort requested; not a safety function";
        if (!devices_->board().emergency_parser())
            note += "; this board's firmware has no emergency parser: it obeys M112 only after "
                    "a blocking command (a heat-up) ends";
        return json{{"estop", true}, {"note", note}};
    });

    // What the operator must reach even when api.max_clients connections are taken.
    for (const char* m : {"server.info", "cell.status", "job.get", "job.pause", "job.abort",
                          "cell.estop"})
        api_->add_control_method(m);
}

}  // namespace fibrecell::daemon::service
