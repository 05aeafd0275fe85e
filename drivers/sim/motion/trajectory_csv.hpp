#pragma once
// The recorded trajectory as CSV for analysis outside the program (fibrecell-simcell
// --trajectory): one row per sample, the TCP in the work object of the move it belongs to.
//   t_s,x_mm,y_mm,z_mm,path_mm,speed_mm_s,segment,source

#include "drivers/sim/motion/motion_simulator.hpp"

#include <ostream>
#include <span>

namespace fibrecell::drivers::sim {

void write_trajectory_csv_header(std::ostream& out);
void write_trajectory_csv_rows(std::ostream& out, std::span<const TrajectorySample> samples);

}  // namespace fibrecell::drivers::sim
