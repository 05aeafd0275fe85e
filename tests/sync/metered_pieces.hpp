#pragma once
// The sync engine's metering rule written out independently of daemon/sync, for the tests that
// rebuild the board's expected log: n = ceil(path / piece) equal pieces, E rounded to 1e-5 on the
// running total, one "G1 E<e> F<feed>" each.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace fibrecell::test {

inline std::vector<std::string> metered_pieces(double path_mm, double e_per_path_mm,
                                               double speed_mm_s, double piece_mm) {
    const int n = static_cast<int>(std::ceil(path_mm / piece_mm - 1e-9));
    const auto r5 = [](double v) { return std::round(v * 1e5) / 1e5; };
    std::vector<std::string> out;
    for (int i = 0; i < n; ++i) {
        const double e = r5(path_mm * e_per_path_mm * (i + 1) / n) - r5(path_mm * e_per_path_mm * i / n);
        char line[64];
        std::snprintf(line, sizeof line, "G1 E%.5f F%.1f", e, speed_mm_s * e_per_path_mm * 60);
        out.emplace_back(line);
    }
    return out;
}

}  // namespace fibrecell::test
