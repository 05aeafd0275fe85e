#include "daemon/history/history_record.hpp"

#include "daemon/jobs/job_journal.hpp"
#include "daemon/jobs/planned_use.hpp"

#include <fstream>
#include <stdexcept>

namespace fibrecell::daemon::history {

using nlohmann::json;

namespace {

json number_or_null(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

std::optional<double> optional_number(const json& j, const char* key) {
    if (!j.contains(key) || j[key].is_null()) return std::nullopt;
    if (!j[key].is_number()) throw std::invalid_argument(std::string(key) + ": expected a number");
    return j[key].get<double>();
}

std::string text(const json& j, const char* key) {
    if (!j.contains(key)) return "";
    if (!j[key].is_string()) throw std::invalid_argument(std::string(key) + ": expected a string");
    return j[key].get<std::string>();
}

}  // namespace

json to_json(const HistoryRecord& r) {
    return {{"id", r.id},
            {"name", r.name},
            {"strategy", r.strategy},
            {"outcome", r.outcome},
            {"reason", r.reason},
            {"submitted_by", r.submitted_by},
            {"started_by", r.started_by},
            {"submitted_at", r.submitted_at},
            {"planned_at", r.planned_at},
            {"started_at", r.started_at},
            {"ended_at", r.ended_at},
            {"layers_printed", r.layers_printed},
            {"layers_total", r.layers_total},
            {"fibre_used_m", number_or_null(r.fibre_used_m)},
            {"fibre_planned_m", number_or_null(r.fibre_planned_m)},
            {"pla_used_m", number_or_null(r.pla_used_m)},
            {"pla_planned_m", number_or_null(r.pla_planned_m)},
            {"cut_error_p99_mm", number_or_null(r.cut_error_p99_mm)}};
}

HistoryRecord history_record_from_json(const json& j) {
    if (!j.is_object()) throw std::invalid_argument("not a JSON object");
    HistoryRecord r;
    if (!j.contains("id") || !j["id"].is_number_integer() || j["id"].get<std::int64_t>() < 1)
        throw std::invalid_argument("id: expected a positive integer");
    r.id = j["id"].get<std::int64_t>();
    r.name = text(j, "name");
    r.strategy = text(j, "strategy");
    r.outcome = text(j, "outcome");
    r.reason = text(j, "reason");
    r.submitted_by = text(j, "submitted_by");
    r.started_by = text(j, "started_by");
    r.submitted_at = text(j, "submitted_at");
    r.planned_at = text(j, "planned_at");
    r.started_at = text(j, "started_at");
    r.ended_at = text(j, "ended_at");
    r.layers_printed = j.value("layers_printed", 0);
    r.layers_total = j.value("layers_total", 0);
    r.fibre_used_m = optional_number(j, "fibre_used_m");
    r.fibre_planned_m = optional_number(j, "fibre_planned_m");
    r.pla_used_m = optional_number(j, "pla_used_m");
    r.pla_planned_m = optional_number(j, "pla_planned_m");
    r.cut_error_p99_mm = optional_number(j, "cut_error_p99_mm");
    return r;
}

HistoryRecord record_of(const jobs::JobRecord& job, const std::filesystem::path& job_dir) {
    HistoryRecord r;
    r.id = job.id;
    r.name = job.name;
    r.outcome = std::string(jobs::to_string(job.state));
    r.reason = job.reason;
    r.submitted_by = job.submitted_by;
    r.started_by = job.started_by;
    r.submitted_at = job.submitted_at;
    r.planned_at = job.planned_at;
    r.started_at = job.started_at;
    r.ended_at = job.ended_at.empty() ? job.updated_at : job.ended_at;  // older state files

    const json report = jobs::read_json_file(job_dir / "plan" / "report.json");
    if (report.is_object()) r.strategy = report.value("strategy", "");
    if (const auto planned = jobs::planned_use(job_dir / "plan")) {
        r.layers_total = planned->layers;
        r.fibre_planned_m = planned->fibre_m;
        r.pla_planned_m = planned->pla_m;
    }

    const auto journal = job_dir / "journal.jsonl";
    if (std::filesystem::exists(journal)) {
        try {
            const jobs::JournalSummary s = jobs::read_journal(journal);
            r.layers_printed = s.layers_done;
            const jobs::JournalUsed used = s.used.value_or(jobs::JournalUsed{});
            r.fibre_used_m = used.fibre_mm / 1000.0;
            r.pla_used_m = used.pla_mm / 1000.0;
        } catch (const std::exception&) {
            // A damaged journal: the job's own state says so; the record goes without figures.
        }
    }
    if (job.state == jobs::JobState::completed || job.state == jobs::JobState::completed_with_warnings)
        r.layers_printed = r.layers_total;

    const json result = jobs::read_json_file(job_dir / "result.json");
    if (result.is_object() && result.contains("cut_error_mm") &&
        result["cut_error_mm"].value("count", 0) > 0)
        r.cut_error_p99_mm = result["cut_error_mm"].value("p99", 0.0);
    return r;
}

}  // namespace fibrecell::daemon::history
