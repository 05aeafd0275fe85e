#include "drivers/sim/motion/trajectory_csv.hpp"

#include <cstdio>

namespace fibrecell::drivers::sim {

void write_trajectory_csv_header(std::ostream& out) {
    out << "t_s,x_mm,y_mm,z_mm,path_mm,speed_mm_s,segment,source\n";
}

void write_trajectory_csv_rows(std::ostream& out, std::span<const TrajectorySample> samples) {
    char row[160];
    for (const TrajectorySample& s : samples) {
        // Microseconds and 0.1 micrometres: finer than the simulator's tick and tolerances.
        std::snprintf(row, sizeof row, "%.6f,%.4f,%.4f,%.4f,%.4f,%.4f,%llu,", s.t_s,
                      s.tcp_wobj_mm.x(), s.tcp_wobj_mm.y(), s.tcp_wobj_mm.z(), s.path_mm,
                      s.speed_mm_s, static_cast<unsigned long long>(s.segment));
        out << row << '"';
        for (const char c : s.source) {
            if (c == '"') out << '"';  // CSV doubles a quote inside a quoted field
            out << c;
        }
        out << "\"\n";
    }
}

}  // namespace fibrecell::drivers::sim
