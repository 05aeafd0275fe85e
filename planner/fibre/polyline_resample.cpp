#include "planner/fibre/polyline_resample.hpp"

#include <algorithm>
#include <cmath>

namespace fibrecell::planner {

std::vector<Eigen::Vector2d> resampled(const std::vector<Eigen::Vector2d>& pts, bool closed,
                                       double step, std::vector<char>* vertex) {
    const std::size_t n = pts.size();
    if (vertex) vertex->clear();
    if (closed && n <= 2) {
        if (vertex) vertex->assign(n, 1);
        return pts;
    }
    std::vector<Eigen::Vector2d> out;
    const std::size_t count = closed ? n : (n == 0 ? 0 : n - 1);
    for (std::size_t k = 0; k < count; ++k) {
        const Eigen::Vector2d& a = pts[k];
        const Eigen::Vector2d& b = pts[(k + 1) % n];
        const int parts = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
        for (int j = 0; j < parts; ++j) {
            out.push_back(a + (b - a) * (static_cast<double>(j) / parts));
            if (vertex) vertex->push_back(j == 0);
        }
    }
    if (!closed && n > 0) {
        out.push_back(pts.back());
        if (vertex) vertex->push_back(1);
    }
    return out;
}

}  // namespace fibrecell::planner
