#include "planner/toolpaths/path_order.hpp"

#include <algorithm>
#include <limits>

namespace fibrecell::planner {
namespace {

// The best way into `path` from `at`: the entry vertex (open paths: 0 or last) and its distance.
struct Entry {
    std::size_t vertex = 0;
    double distance_sq = std::numeric_limits<double>::infinity();
};

Entry nearest_entry(const Toolpath& path, const Eigen::Vector2d& at) {
    Entry best;
    if (path.points.empty()) return best;
    auto consider = [&](std::size_t i) {
        const double d = (path.points[i] - at).squaredNorm();
        if (d < best.distance_sq) best = {i, d};
    };
    if (path.closed) {
        for (std::size_t i = 0; i < path.points.size(); ++i) consider(i);
    } else {
        consider(0);
        consider(path.points.size() - 1);
    }
    return best;
}

void enter_at(Toolpath& path, std::size_t vertex) {
    if (vertex == 0) return;
    if (path.closed)
        std::rotate(path.points.begin(), path.points.begin() + static_cast<std::ptrdiff_t>(vertex),
                    path.points.end());
    else
        std::reverse(path.points.begin(), path.points.end());
}

}  // namespace

Eigen::Vector2d path_start(const Toolpath& path) {
    return path.points.empty() ? Eigen::Vector2d::Zero() : path.points.front();
}

Eigen::Vector2d path_end(const Toolpath& path) {
    if (path.points.empty()) return Eigen::Vector2d::Zero();
    return path.closed ? path.points.front() : path.points.back();
}

double path_length(const Toolpath& path) {
    double length = 0;
    for (std::size_t i = 1; i < path.points.size(); ++i)
        length += (path.points[i] - path.points[i - 1]).norm();
    if (path.closed && path.points.size() > 2)
        length += (path.points.front() - path.points.back()).norm();
    return length;
}

std::vector<Toolpath> order_nearest(std::vector<Toolpath> paths, const Eigen::Vector2d& start_mm) {
    std::vector<Toolpath> ordered;
    ordered.reserve(paths.size());
    std::vector<bool> taken(paths.size(), false);
    Eigen::Vector2d at = start_mm;
    for (std::size_t k = 0; k < paths.size(); ++k) {
        std::size_t best = paths.size();
        Entry best_entry;
        for (std::size_t i = 0; i < paths.size(); ++i) {
            if (taken[i]) continue;
            const Entry e = nearest_entry(paths[i], at);
            if (best == paths.size() || e.distance_sq < best_entry.distance_sq) {
                best = i;
                best_entry = e;
            }
        }
        taken[best] = true;
        enter_at(paths[best], best_entry.vertex);
        at = path_end(paths[best]);
        ordered.push_back(std::move(paths[best]));
    }
    return ordered;
}

}  // namespace fibrecell::planner
