#include "daemon/history/history_csv.hpp"

#include <cstdio>
#include <optional>

namespace fibrecell::daemon::history {

namespace {

std::string csv_number(const std::optional<double>& v) {
    if (!v) return "";
    char text[32];
    std::snprintf(text, sizeof text, "%.5f", *v);  // 0.01 mm
    return text;
}

}  // namespace

std::string csv_text(std::string_view field) {
    std::string out;
    if (!field.empty() && (field[0] == '=' || field[0] == '+' || field[0] == '-' ||
                           field[0] == '@' || field[0] == '\t' || field[0] == '\r'))
        out = "'";
    out += field;
    if (out.find_first_of(",\"\r\n") == std::string::npos) return out;
    std::string quoted = "\"";
    for (char c : out) {
        if (c == '"') quoted += '"';
        quoted += c;
    }
    return quoted + "\"";
}

std::string to_csv(const std::vector<HistoryRecord>& records) {
    std::string out =
        "id,name,strategy,outcome,reason,submitted_by,started_by,submitted_at,planned_at,"
        "started_at,ended_at,layers_printed,layers_total,fibre_used_m,fibre_planned_m,pla_used_m,"
        "pla_planned_m,cut_error_p99_mm\r\n";
    for (const HistoryRecord& r : records) {
        const std::string fields[] = {std::to_string(r.id),
                                      csv_text(r.name),
                                      csv_text(r.strategy),
                                      csv_text(r.outcome),
                                      csv_text(r.reason),
                                      csv_text(r.submitted_by),
                                      csv_text(r.started_by),
                                      csv_text(r.submitted_at),
                                      csv_text(r.planned_at),
                                      csv_text(r.started_at),
                                      csv_text(r.ended_at),
                                      std::to_string(r.layers_printed),
                                      std::to_string(r.layers_total),
                                      csv_number(r.fibre_used_m),
                                      csv_number(r.fibre_planned_m),
                                      csv_number(r.pla_used_m),
                                      csv_number(r.pla_planned_m),
                                      csv_number(r.cut_error_p99_mm)};
        bool first = true;
        for (const std::string& f : fields) {
            if (!first) out += ',';
            out += f;
            first = false;
        }
        out += "\r\n";
    }
    return out;
}

}  // namespace fibrecell::daemon::history
