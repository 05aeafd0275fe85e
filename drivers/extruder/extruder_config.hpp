#pragma once
// The `extruder:` section of the cell YAML: the GT2560 link and what the extruder controller
// needs to turn print events into Marlin commands. Units are in the key names.

#include "config/yaml_section.hpp"
#include "drivers/marlin/marlin_link.hpp"

#include <string>

namespace fibrecell::drivers {

enum class CutMethod {
    pin,      // M400, then M42 P<pin> S255 / S0 (DIRECT_PIN_CONTROL; relay or MOSFET)
    servo,    // M400, then M280 P<index> S<angle>
    spindle,  // M3 / M5: SPINDLE_FEATURE, Marlin synchronises them with the planner itself
};

struct CutterConfig {
    CutMethod method = CutMethod::pin;
    int pin = 11;                 // GT2560 A+/V3 servo header D11
    int servo_index = 0;
    double cut_angle_deg = 90;
    double open_angle_deg = 0;
    int hold_ms = 200;            // blade closed this long
};

struct ExtruderConfig {
    marlin::MarlinLinkConfig link;
    int pla_tool = 0;                     // E0
    int ccf_tool = 1;                     // E1
    // The nozzles mounted (hardware: a job that states another is refused) and the hotend
    // temperatures a job may ask for; the print's temperatures are the job's.
    double pla_nozzle_diameter_mm = 0.8;
    double ccf_nozzle_diameter_mm = 1.0;
    double pla_max_temp_c = 260;          // Marlin: HEATER_n_MAXTEMP 275 less its 15 degC margin
    double ccf_max_temp_c = 260;
    double min_extrude_temp_c = 170;      // Marlin EXTRUDE_MINTEMP: colder, E moves are refused
    double filament_diameter_mm = 1.75;   // PLA
    double retract_mm = 1.0;
    double retract_speed_mm_s = 40;     // Marlin FWRETRACT default 45; the prime before a PLA path takes retract_mm / this
    double cutter_distance_mm = 42;       // cutter to nozzle tip (hardware): the thread feed at a
                                          // path start and where the planner puts the cut
    double thread_speed_mm_s = 5;
    double max_extrusion_length_mm = 200; // Marlin EXTRUDE_MAXLENGTH: longer moves are split
    double max_feed_mm_s = 50;            // highest E feed rate accepted
    CutterConfig cutter;
};

// Reads and checks the section (bounds, unknown keys); throws config::ConfigError naming the key.
ExtruderConfig load_extruder_config(config::Section section);

}  // namespace fibrecell::drivers
