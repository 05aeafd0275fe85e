#include "daemon/print/print_settings.hpp"

#include <cmath>
#include <sstream>

namespace fibrecell::daemon::print {
namespace {

std::string number(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

[[noreturn]] void refuse(const planner::JobSpec& job, const std::string& what) {
    throw SettingsError(job.job_file + ": " + what);
}

HeadSettings head_settings(const planner::JobSpec& job, const planner::HeadProcessSpec& spec,
                           const CellConfig& cell, drivers::abb::Nozzle nozzle) {
    const bool pla = nozzle == drivers::abb::Nozzle::pla;
    const std::string key = pla ? "process.pla." : "process.ccf.";
    const std::string cell_key = pla ? "extruder.pla." : "extruder.ccf.";
    const auto& x = cell.extruder;
    HeadSettings h;
    h.temp_c = spec.nozzle_temp_c;
    const double max_c = pla ? x.pla_max_temp_c : x.ccf_max_temp_c;
    if (h.temp_c > max_c)
        refuse(job, key + "nozzle_temp_c: " + number(h.temp_c) + " degC is above the cell's limit " +
                        number(max_c) + " degC (" + cell_key + "max_temp_c)");
    if (h.temp_c < x.min_extrude_temp_c)
        refuse(job, key + "nozzle_temp_c: " + number(h.temp_c) + " degC is below " +
                        number(x.min_extrude_temp_c) +
                        " degC, where the firmware refuses to extrude (extruder.min_extrude_temp_c)");
    h.speed_mm_s = spec.speed_mm_s;
    h.travel_speed_mm_s = spec.travel_speed_mm_s;
    const double max_travel = cell.robot.motion.max_travel_speed_mm_s;
    if (h.travel_speed_mm_s > max_travel)
        refuse(job, key + "travel_speed_mm_s: " + number(h.travel_speed_mm_s) +
                        " mm/s is above the cell's limit " + number(max_travel) +
                        " mm/s (robot.motion.max_travel_speed_mm_s)");
    h.line_width_mm = spec.line_width_mm;
    h.layer_height_mm = pla ? job.layers.pla_layer_height_mm : job.layers.ccf_layer_height_mm;
    h.nozzle_diameter_mm = pla ? x.pla_nozzle_diameter_mm : x.ccf_nozzle_diameter_mm;
    if (spec.nozzle_diameter_mm && *spec.nozzle_diameter_mm != h.nozzle_diameter_mm)
        refuse(job, key + "nozzle_diameter_mm: " + number(*spec.nozzle_diameter_mm) +
                        " mm, but the cell's " + (pla ? "PLA" : "CCF") + " nozzle is " +
                        number(h.nozzle_diameter_mm) + " mm (" + cell_key +
                        "nozzle_diameter_mm): change the nozzle or leave the key out");
    return h;
}

double required(const nlohmann::json& j, const char* key) {
    if (!j.contains(key) || !j[key].is_number())
        throw std::invalid_argument(std::string("settings.") + key + ": a number is required");
    return j[key].get<double>();
}

nlohmann::json head_json(const HeadSettings& h) {
    return {{"temp_c", h.temp_c},
            {"speed_mm_s", h.speed_mm_s},
            {"travel_speed_mm_s", h.travel_speed_mm_s},
            {"line_width_mm", h.line_width_mm},
            {"layer_height_mm", h.layer_height_mm},
            {"nozzle_diameter_mm", h.nozzle_diameter_mm}};
}

HeadSettings head_from_json(const nlohmann::json& j, const char* head) {
    if (!j.contains(head) || !j[head].is_object())
        throw std::invalid_argument(std::string("settings.") + head + ": an object is required");
    const nlohmann::json& o = j[head];
    HeadSettings h;
    h.temp_c = required(o, "temp_c");
    h.speed_mm_s = required(o, "speed_mm_s");
    h.travel_speed_mm_s = required(o, "travel_speed_mm_s");
    h.line_width_mm = required(o, "line_width_mm");
    h.layer_height_mm = required(o, "layer_height_mm");
    h.nozzle_diameter_mm = required(o, "nozzle_diameter_mm");
    return h;
}

}  // namespace

drivers::abb::ProgramOptions PrintSettings::program_options() const {
    drivers::abb::ProgramOptions o;
    o.pla_speed_mm_s = pla.speed_mm_s;
    o.ccf_speed_mm_s = ccf.speed_mm_s;
    o.pla_travel_speed_mm_s = pla.travel_speed_mm_s;
    o.ccf_travel_speed_mm_s = ccf.travel_speed_mm_s;
    o.cutter_distance_mm = cutter_distance_mm;
    return o;
}

void PrintSettings::apply_to(sync::SyncOptions& options) const {
    options.hotends = hotends();
    options.pla_line_width_mm = pla.line_width_mm;
    options.pla_layer_height_mm = pla.layer_height_mm;
}

PrintSettings print_settings(const planner::JobSpec& job, const CellConfig& cell) {
    PrintSettings s;
    s.pla = head_settings(job, job.process.pla, cell, drivers::abb::Nozzle::pla);
    s.ccf = head_settings(job, job.process.ccf, cell, drivers::abb::Nozzle::ccf);
    s.cutter_distance_mm = cell.extruder.cutter_distance_mm;
    if (const auto& stated = job.planner.cutter_distance_mm; stated && *stated != s.cutter_distance_mm)
        refuse(job, "planner.cutter_distance_mm: " + number(*stated) +
                        " mm, but the cell's cutter sits " + number(s.cutter_distance_mm) +
                        " mm before the nozzle tip (extruder.ccf.cutter_distance_mm): leave the "
                        "key out, the cell's value is used");
    return s;
}

nlohmann::json to_json(const PrintSettings& s) {
    return {{"pla", head_json(s.pla)},
            {"ccf", head_json(s.ccf)},
            {"cutter_distance_mm", s.cutter_distance_mm}};
}

PrintSettings settings_from_json(const nlohmann::json& j) {
    if (!j.is_object()) throw std::invalid_argument("settings: an object is required");
    PrintSettings s;
    s.pla = head_from_json(j, "pla");
    s.ccf = head_from_json(j, "ccf");
    s.cutter_distance_mm = required(j, "cutter_distance_mm");
    return s;
}

}  // namespace fibrecell::daemon::print
