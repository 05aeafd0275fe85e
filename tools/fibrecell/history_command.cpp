#include "tools/fibrecell/history_command.hpp"

#include "tools/fibrecell/service_connection.hpp"

#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

namespace fibrecell::tools {
namespace {

using nlohmann::json;

std::string metres(const json& r, const char* key) {
    if (!r.contains(key) || !r[key].is_number()) return "-";
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", r[key].get<double>());
    return text;
}

std::string history_table(const json& answer) {
    std::ostringstream out;
    const json& records = answer["records"];
    if (records.empty()) return "no jobs in the history\n";
    out << "job  ended                 outcome                  layers   fibre m used/plan   "
           "PLA m used/plan   name (started by)\n";
    for (const json& r : records) {
        char line[256];
        std::snprintf(line, sizeof line, "%-4lld %-21s %-24s %3d/%-4d %8s/%-9s %8s/%-8s ",
                      static_cast<long long>(r.value("id", 0)), r.value("ended_at", "").c_str(),
                      r.value("outcome", "").c_str(), r.value("layers_printed", 0),
                      r.value("layers_total", 0), metres(r, "fibre_used_m").c_str(),
                      metres(r, "fibre_planned_m").c_str(), metres(r, "pla_used_m").c_str(),
                      metres(r, "pla_planned_m").c_str());
        out << line << r.value("name", "");
        if (!r.value("started_by", "").empty()) out << " (" << r.value("started_by", "") << ")";
        out << "\n";
        if (!r.value("reason", "").empty()) out << "     " << r.value("reason", "") << "\n";
    }
    return out.str();
}

}  // namespace

void add_history_command(CLI::App& app, int& exit_code) {
    auto* cmd = app.add_subcommand("history", "the jobs the cell ended and what they used");
    auto c = std::make_shared<Connection>();
    auto since = std::make_shared<std::string>();
    auto limit = std::make_shared<std::int64_t>(0);
    auto csv = std::make_shared<bool>(false);
    cmd->add_option("--since", *since, "only jobs that ended on or after DATE (2026-12-07)");
    cmd->add_option("--limit", *limit, "only the newest N")->check(CLI::PositiveNumber);
    auto* csv_flag = cmd->add_flag("--csv", *csv, "CSV for a spreadsheet (RFC 4180, a header row)");
    add_connection_options(*cmd, *c);
    if (auto* json_flag = cmd->get_option_no_throw("--json")) csv_flag->excludes(json_flag);
    cmd->callback([&exit_code, c, since, limit, csv] {
        guarded(exit_code, [&] {
            json params = json::object();
            if (!since->empty()) params["since"] = *since;
            if (*limit > 0) params["limit"] = *limit;
            if (*csv) params["format"] = "csv";
            api::ApiClient client = c->connect();
            const json answer = client.call("history.list", params);
            if (*csv) {
                std::cout << answer.value("csv", "");
                return 0;
            }
            print(*c, answer, history_table(answer));
            return 0;
        });
    });
}

}  // namespace fibrecell::tools
