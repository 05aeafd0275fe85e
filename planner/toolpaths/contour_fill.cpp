#include "planner/toolpaths/contour_fill.hpp"

#include "planner/toolpaths/path_order.hpp"
#include "planner/toolpaths/polygon_offset.hpp"
#include "planner/toolpaths/zigzag_fill.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace fibrecell::planner {
namespace {

std::vector<Toolpath> island_paths(const std::vector<Polygon>& island,
                                   const ContourFillOptions& options,
                                   const Eigen::Vector2d& start) {
    const OffsetOptions offset{options.arc_tolerance_mm};
    std::vector<Toolpath> rings;
    for (int i = 0; i < options.rings; ++i) {
        std::vector<Polygon> loops =
            offset_region(island, -contour_ring_inset_mm(i, options), offset);
        if (loops.empty()) break;
        for (Polygon& loop : loops) rings.push_back({options.ring_role, true, std::move(loop)});
    }
    rings = order_nearest(std::move(rings), start);

    const std::vector<Polygon> fill_region =
        offset_region(island, -contour_fill_inset_mm(options), offset);
    std::vector<Toolpath> fill = zigzag_fill(fill_region, options.fill_role,
                                             {std::max(options.pitch_mm, options.fill_spacing_mm),
                                              options.angle_deg, options.max_link_spacings});
    fill = order_nearest(std::move(fill), rings.empty() ? start : path_end(rings.back()));

    rings.insert(rings.end(), std::make_move_iterator(fill.begin()),
                 std::make_move_iterator(fill.end()));
    return rings;
}

double squared_distance_to_loop(const Polygon& loop, const Eigen::Vector2d& at) {
    double best = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector2d& p : loop) best = std::min(best, (p - at).squaredNorm());
    return best;
}

}  // namespace

namespace {

// Round joins are chords up to 2.25 arc tolerances inside their arcs (see offset_region).
double chord_margin_mm(const ContourFillOptions& options) {
    return options.ribbons_overlap ? 0.0 : 2.5 * options.arc_tolerance_mm;
}

}  // namespace

double contour_ring_inset_mm(int ring, const ContourFillOptions& options) {
    return options.pitch_mm / 2 + ring * options.pitch_mm + chord_margin_mm(options);
}

double contour_fill_inset_mm(const ContourFillOptions& options) {
    const double rings = options.rings;
    if (options.ribbons_overlap) return std::max(rings, 0.5) * options.pitch_mm;
    // A whole pitch inside the innermost ring's inset (margin included), plus the margin for the
    // region's own chords.
    return (rings + 0.5) * options.pitch_mm + 2 * chord_margin_mm(options);
}

std::vector<Toolpath> contour_fill(const LayerOutline& outline, const ContourFillOptions& options) {
    if (!(options.pitch_mm > 0) || !std::isfinite(options.pitch_mm))
        throw std::invalid_argument("contour fill pitch_mm (line width) must be positive");
    if (options.rings < 0) throw std::invalid_argument("contour fill rings must not be negative");

    std::vector<std::vector<Polygon>> islands = split_islands(outline.loops);
    std::vector<Toolpath> paths;
    std::vector<bool> done(islands.size(), false);
    Eigen::Vector2d at = options.start_mm;
    for (std::size_t k = 0; k < islands.size(); ++k) {
        // Next island: the one whose outer loop comes nearest to the nozzle.
        std::size_t next = islands.size();
        double next_distance = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < islands.size(); ++i) {
            if (done[i]) continue;
            const double d = squared_distance_to_loop(islands[i].front(), at);
            if (next == islands.size() || d < next_distance) {
                next = i;
                next_distance = d;
            }
        }
        done[next] = true;
        std::vector<Toolpath> island = island_paths(islands[next], options, at);
        if (!island.empty()) at = path_end(island.back());
        paths.insert(paths.end(), std::make_move_iterator(island.begin()),
                     std::make_move_iterator(island.end()));
    }
    return paths;
}

}  // namespace fibrecell::planner
