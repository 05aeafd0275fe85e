#pragma once
// The filament a plan will feed, from its plan directory: the fibre paths (each threaded at its
// start, so fibre fed equals path length: report.json's fibre length) and the PLA paths as
// filament (report.json's PLA path length times print.json's pla_e_per_path_mm). What the
// history sets beside the board's count, and what the spools must hold for a start.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>

namespace fibrecell::daemon::jobs {

struct PlannedUse {
    double fibre_m = 0;
    double pla_m = 0;  // filament
    int layers = 0;
};

// A JSON file of a job's folder (report.json, result.json); null when it is missing or not JSON.
nlohmann::json read_json_file(const std::filesystem::path& p);

// nullopt when the plan's report.json or print.json is missing or unreadable.
std::optional<PlannedUse> planned_use(const std::filesystem::path& plan_dir);

}  // namespace fibrecell::daemon::jobs
