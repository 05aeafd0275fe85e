#pragma once
// The few board commands the sync engine adds to ExtruderController's: waiting for one hotend,
// waiting for queued moves, and the PLA line's E per mm of path (to meter extrude_pla in pieces).

#include "drivers/extruder/extruder_controller.hpp"

#include <string>

namespace fibrecell::daemon::sync {

// "M109 T<tool> S<temp>": heat the head's hotend to the print's temperature and wait.
std::string heat_and_wait(const drivers::ExtruderConfig& config, drivers::Head head, double temp_c);

// "M400": the ok comes once every queued move has run (the thread feed is in the nozzle).
std::string wait_for_moves();

// E [mm of filament] per mm of path for a PLA line `line_width_mm` x `layer_height_mm`: the
// line's cross-section over the filament's, as ExtruderController::extrude_pla computes it.
double pla_e_per_path_mm(const drivers::ExtruderConfig& config, double line_width_mm,
                         double layer_height_mm);

}  // namespace fibrecell::daemon::sync
