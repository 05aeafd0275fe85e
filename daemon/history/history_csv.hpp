#pragma once
// The history as CSV for spreadsheets (docs/history.md, "CSV"): RFC 4180 (a header row, CRLF
// line ends, a field with a comma, quote or line break in double quotes, quotes doubled), and
// a text field that a spreadsheet would run as a formula (one starting with = + - @, a tab or a
// carriage return) prefixed with an apostrophe, as OWASP advises against CSV injection: the
// spreadsheet shows it as text; a program reading the file drops that one apostrophe.

#include "daemon/history/history_record.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::daemon::history {

// id,name,strategy,outcome,reason,submitted_by,started_by,submitted_at,planned_at,started_at,
// ended_at,layers_printed,layers_total,fibre_used_m,fibre_planned_m,pla_used_m,pla_planned_m,
// cut_error_p99_mm
std::string to_csv(const std::vector<HistoryRecord>& records);

// One text field as written (formula prefix, then quoting).
std::string csv_text(std::string_view field);

}  // namespace fibrecell::daemon::history
