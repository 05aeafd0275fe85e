#include "daemon/sync/board_commands.hpp"

#include <cmath>
#include <numbers>

namespace fibrecell::daemon::sync {

std::string heat_and_wait(const drivers::ExtruderConfig& config, drivers::Head head,
                          double temp_c) {
    const int tool = head == drivers::Head::pla ? config.pla_tool : config.ccf_tool;
    return "M109 T" + std::to_string(tool) + " S" + std::to_string(std::lround(temp_c));
}

std::string wait_for_moves() { return "M400"; }

double pla_e_per_path_mm(const drivers::ExtruderConfig& config, double line_width_mm,
                         double layer_height_mm) {
    const double d = config.filament_diameter_mm;
    return line_width_mm * layer_height_mm / (std::numbers::pi * d * d / 4.0);
}

}  // namespace fibrecell::daemon::sync
