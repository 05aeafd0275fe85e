#pragma once
// One line of the cell's history (docs/history.md): a job that ended — completed, aborted,
// failed (in planning or printing) or interrupted — with who asked for it, when, what it used and
// how it went. The used figures are the extruder board's (the link's feed ledger, journaled as
// the print ran), the planned ones the plan's, side by side.

#include "daemon/jobs/job_record.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace fibrecell::daemon::history {

struct HistoryRecord {
    std::int64_t id = 0;
    std::string name, strategy;
    std::string outcome;  // the job's state: completed, completed_with_warnings, aborted, ...
    std::string reason;
    std::string submitted_by, started_by;
    std::string submitted_at, planned_at, started_at, ended_at;  // UTC, ISO 8601; "" not reached
    int layers_printed = 0, layers_total = 0;
    std::optional<double> fibre_used_m, pla_used_m;  // none: it never printed
    std::optional<double> fibre_planned_m, pla_planned_m;  // none: no plan
    std::optional<double> cut_error_p99_mm;          // none: no cut was measured
};

nlohmann::json to_json(const HistoryRecord& r);
// Throws std::invalid_argument naming the key.
HistoryRecord history_record_from_json(const nlohmann::json& j);

// The record of a job that ended, from its record and the files of its folder (plan/report.json,
// plan/print.json, result.json, journal.jsonl); a missing or unreadable file leaves its figures
// out.
HistoryRecord record_of(const jobs::JobRecord& job, const std::filesystem::path& job_dir);

}  // namespace fibrecell::daemon::history
