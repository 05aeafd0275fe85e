#include "daemon/jobs/planned_use.hpp"

#include <nlohmann/json.hpp>

#include <fstream>

namespace fibrecell::daemon::jobs {

nlohmann::json read_json_file(const std::filesystem::path& p) {
    std::ifstream in(p);
    if (!in) return nullptr;
    try {
        return nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception&) {
        return nullptr;
    }
}

std::optional<PlannedUse> planned_use(const std::filesystem::path& plan_dir) {
    const nlohmann::json report = read_json_file(plan_dir / "report.json");
    const nlohmann::json print = read_json_file(plan_dir / "print.json");
    if (!report.is_object() || !print.is_object() || !print.contains("board")) return std::nullopt;
    try {
        PlannedUse u;
        if (report.contains("fibre")) u.fibre_m = report["fibre"].value("length_m", 0.0);
        if (report.contains("pla"))
            u.pla_m = report["pla"].value("length_m", 0.0) *
                      print["board"].value("pla_e_per_path_mm", 0.0);
        if (report.contains("layers"))
            u.layers = report["layers"].value("pla", 0) + report["layers"].value("ccf", 0);
        return u;
    } catch (const nlohmann::json::exception&) {
        return std::nullopt;
    }
}

}  // namespace fibrecell::daemon::jobs
