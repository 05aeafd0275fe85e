#pragma once
// Points every W/16 along fibre paths, each with its path and its distance along it: what the
// fibre tests measure spacing on, brute force or nearly, independently of the planner's checks.

#include "spacing.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <vector>

namespace fibrecell::test {

struct PathSample {
    Eigen::Vector2d p;
    int path;
    double along;     // from the path's first point [mm]
    double loop = 0;  // a closed path's length (distances along it go the shorter way), else 0
};

// `Path`: anything with `points` and `closed` (LaidPiece, Toolpath). A closed path is sampled
// round to its start, which it does not repeat.
template <class Path>
std::vector<PathSample> path_samples(const std::vector<Path>& paths, int first_path = 0) {
    std::vector<PathSample> out;
    for (std::size_t i = 0; i < paths.size(); ++i) {
        const int id = first_path + static_cast<int>(i);
        std::vector<Eigen::Vector2d> pts = paths[i].points;
        if (paths[i].closed) pts.push_back(pts.front());
        const std::size_t first = out.size();
        double along = 0;
        for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
            const double l = (pts[k + 1] - pts[k]).norm();
            const int n = std::max(1, static_cast<int>(std::ceil(l / (W / 16))));
            for (int j = 0; j < n; ++j)
                out.push_back({pts[k] + (pts[k + 1] - pts[k]) * (double(j) / n), id, along + l * j / n});
            along += l;
        }
        if (!paths[i].closed) out.push_back({pts.back(), id, along});
        if (paths[i].closed)
            for (std::size_t s = first; s < out.size(); ++s) out[s].loop = along;
    }
    return out;
}

// How far apart along their path two samples of it are.
inline double apart_along(const PathSample& a, const PathSample& b) {
    const double d = std::abs(a.along - b.along);
    return a.loop > 0 ? std::min(d, a.loop - d) : d;
}

}  // namespace fibrecell::test
