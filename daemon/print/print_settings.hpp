#pragma once
// The one mapping from a job and the cell that prints it to the print's settings: what the
// robot program, the RAPID speed data and the board commands are made from. Every job setting
// takes effect here or the job is refused (docs/job-format.md, "What the cell decides"):
//
//   process.*.nozzle_temp_c       -> M104/M109 (the cell's min_extrude_temp_c .. max_temp_c)
//   process.*.speed_mm_s          -> print moves' speed data
//   process.*.travel_speed_mm_s   -> lift, travel and turn speed data (up to the cell's
//                                    robot.motion.max_travel_speed_mm_s)
//   process.pla.line_width_mm     -> the PLA flow (E per mm of path), with layers.pla_layer_height_mm
//   process.*.nozzle_diameter_mm  -> must be the cell's mounted nozzle (hardware)
//   planner.cutter_distance_mm    -> must be the cell's extruder.ccf.cutter_distance_mm (hardware)
//
// Planning computes them once and writes them to the plan directory (print.json); the print
// uses what the plan says, never the job again.

#include "daemon/cell/cell_config.hpp"
#include "daemon/sync/sync_options.hpp"
#include "drivers/abb/program/print_program.hpp"
#include "planner/job/job_spec.hpp"

#include <nlohmann/json.hpp>

#include <stdexcept>

namespace fibrecell::daemon::print {

struct HeadSettings {
    double temp_c = 0;              // hotend [degC]
    double speed_mm_s = 0;          // printing
    double travel_speed_mm_s = 0;   // lift, travel, head turn with this nozzle
    double line_width_mm = 0;       // PLA line / CCF ribbon
    double layer_height_mm = 0;
    double nozzle_diameter_mm = 0;  // the cell's
};

struct PrintSettings {
    HeadSettings pla, ccf;
    double cutter_distance_mm = 0;  // the cell's: thread feed and the cut before each path end

    drivers::abb::ProgramOptions program_options() const;
    drivers::HotendTargets hotends() const { return {pla.temp_c, ccf.temp_c}; }
    // The sync engine's job-dependent options: temperatures and the PLA line.
    void apply_to(sync::SyncOptions& options) const;
};

// A job setting the cell cannot print; the message names the job's key, the cell's and both
// values.
class SettingsError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

PrintSettings print_settings(const planner::JobSpec& job, const CellConfig& cell);

// print.json's "settings" and back. from_json throws std::invalid_argument naming the key.
nlohmann::json to_json(const PrintSettings& s);
PrintSettings settings_from_json(const nlohmann::json& j);

}  // namespace fibrecell::daemon::print
