#include "daemon/history/history_component.hpp"

#include "config/utc_time.hpp"
#include "daemon/api/api_error.hpp"
#include "daemon/api/params.hpp"
#include "daemon/history/history_csv.hpp"
#include "daemon/history/history_file.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <regex>

namespace fibrecell::daemon::history {

using api::CallContext;
using jobs::JobRecord;
using jobs::JobState;
using nlohmann::json;

namespace {

bool at_an_end(JobState s) { return jobs::is_ended(s) || s == JobState::interrupted; }

// When a job ended, as its record says (state files from before ended_at: its last change).
std::string ended_at(const JobRecord& r) { return r.ended_at.empty() ? r.updated_at : r.ended_at; }

// "2026-12-07" or "2026-12-07T14:00:00Z": compared with the records' ISO times as text.
std::string since_param(api::ParamReader& p) {
    const std::string since = p.string("since");
    static const std::regex date(R"(\d{4}-\d{2}-\d{2}(T\d{2}:\d{2}(:\d{2})?Z?)?)");
    if (!std::regex_match(since, date))
        p.fail("since", "'" + since + "' is not a date (2026-12-07 or 2026-12-07T14:00:00Z)");
    return since;
}

}  // namespace

HistoryComponent::HistoryComponent(jobs::JobsComponent& jobs, printer::PrinterComponent& printer,
                                   const CellConfig& cell, HistoryConfig config)
    : jobs_(jobs), config_(config),
      file_(std::filesystem::path(cell.state_dir) / "history.jsonl") {
    jobs_.on_change([this](const JobRecord& r) { take(r); });
    printer.on_print_finished([this](std::int64_t id) {
        try {
            take(jobs_.store().get(id));
        } catch (const jobs::JobNotFound&) {
        }
    });
}

void HistoryComponent::register_endpoints(component::Endpoints& endpoints) {
    endpoints.method("history.list", [this](const json& params, const CallContext& ctx) {
        api::ParamReader p(ctx.method, params);
        const std::string since = p.has("since") ? since_param(p) : "";
        const auto limit = p.integer_or("limit", 0, 0, std::numeric_limits<std::int32_t>::max());
        const auto format = p.string_opt("format").value_or("json");
        if (format != "json" && format != "csv") p.fail("format", "must be json or csv");
        p.finish();
        std::vector<HistoryRecord> chosen;
        {
            std::lock_guard lock(mu_);
            for (const HistoryRecord& r : records_)
                if (r.ended_at >= since) chosen.push_back(r);
        }
        if (limit > 0 && chosen.size() > static_cast<std::size_t>(limit))
            chosen.erase(chosen.begin(), chosen.end() - limit);  // the newest
        if (format == "csv") return json{{"csv", to_csv(chosen)}, {"count", chosen.size()}};
        json records = json::array();
        for (const HistoryRecord& r : chosen) records.push_back(to_json(r));
        return json{{"records", records}, {"count", chosen.size()}};
    });
    endpoints.event(api::notify::history);
    endpoints_ = endpoints;
}

void HistoryComponent::start() {
    const HistoryRead read = read_history(file_);
    for (const std::string& s : read.skipped) spdlog::error("history.record_unreadable {}", s);
    {
        std::lock_guard lock(mu_);
        records_ = read.records;
    }
    // Jobs that ended while nobody recorded them: interrupted by a crash, or the service stopped
    // between a job's end and its record. Not those recorded at that end already, nor those that
    // ended before the newest record (the retention dropped them: they stay dropped); times are
    // to the second, so within the newest record's second the higher job id counts as later.
    std::pair<std::string, std::int64_t> newest;
    {
        std::lock_guard lock(mu_);
        for (const HistoryRecord& h : records_) newest = std::max(newest, {h.ended_at, h.id});
    }
    for (const JobRecord& r : jobs_.store().list()) {
        if (!at_an_end(r.state)) continue;
        const std::string ended = ended_at(r);
        bool recorded = false;
        {
            std::lock_guard lock(mu_);
            recorded = std::any_of(records_.begin(), records_.end(), [&](const HistoryRecord& h) {
                return h.id == r.id && h.ended_at == ended;
            });
        }
        if (!recorded && std::pair{ended, r.id} > newest) take(r);
    }
}

void HistoryComponent::take(const JobRecord& job) {
    if (!at_an_end(job.state)) return;
    const HistoryRecord record = record_of(job, jobs_.store().job_dir(job.id));
    std::lock_guard lock(mu_);
    const auto old = std::find_if(records_.begin(), records_.end(),
                                  [&](const HistoryRecord& r) { return r.id == job.id; });
    if (old != records_.end()) {
        if (to_json(*old) == to_json(record)) return;  // nothing new
        records_.erase(old);
    }
    records_.push_back(record);
    spdlog::info("history.recorded job {} {}", record.id, record.outcome);
    retain();
    save();
    endpoints_.publish({.topic = api::topic::history,
                        .method = api::notify::history,
                        .params = to_json(record),
                        .delivery = api::Delivery::every});
}

void HistoryComponent::retain() {
    std::vector<HistoryRecord> dropped;
    const std::string oldest_kept =
        config_.keep_days > 0
            ? config::utc_at(std::chrono::system_clock::now() - std::chrono::days(config_.keep_days))
            : "";
    std::erase_if(records_, [&](const HistoryRecord& r) {
        if (r.ended_at >= oldest_kept) return false;
        dropped.push_back(r);
        return true;
    });
    const auto keep = static_cast<std::size_t>(config_.keep);
    if (records_.size() > keep) {
        const auto cut = records_.begin() + static_cast<std::ptrdiff_t>(records_.size() - keep);
        dropped.insert(dropped.end(), records_.begin(), cut);
        records_.erase(records_.begin(), cut);
    }
    for (const HistoryRecord& r : dropped) {
        spdlog::info("history.dropped job {} (ended {})", r.id, r.ended_at);
        if (config_.prune_plans) jobs_.store().remove_plan(r.id);
    }
}

void HistoryComponent::save() {
    try {
        write_history(file_, records_);
    } catch (const std::exception& e) {
        spdlog::error("history.not_saved {}: the records hold until the next change", e.what());
    }
}

}  // namespace fibrecell::daemon::history
