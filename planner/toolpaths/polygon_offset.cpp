#include "planner/toolpaths/polygon_offset.hpp"

#include <polyclipping/clipper.hpp>

#include <cmath>
#include <stdexcept>
#include <string>

namespace fibrecell::planner {
namespace {

constexpr double units_per_mm = 1e5;

ClipperLib::Paths to_clipper(const std::vector<Polygon>& loops) {
    ClipperLib::Paths paths;
    paths.reserve(loops.size());
    for (std::size_t i = 0; i < loops.size(); ++i) {
        const Polygon& loop = loops[i];
        if (loop.size() < 3)
            throw std::invalid_argument("outline loop " + std::to_string(i) + " has " +
                                        std::to_string(loop.size()) + " points (needs 3)");
        ClipperLib::Path path;
        path.reserve(loop.size());
        for (const Eigen::Vector2d& p : loop) {
            if (!std::isfinite(p.x()) || !std::isfinite(p.y()))
                throw std::invalid_argument("outline loop " + std::to_string(i) +
                                            " has a non-finite coordinate");
            path.emplace_back(std::llround(p.x() * units_per_mm),
                              std::llround(p.y() * units_per_mm));
        }
        paths.push_back(std::move(path));
    }
    return paths;
}

Polygon from_clipper(const ClipperLib::Path& path) {
    Polygon loop;
    loop.reserve(path.size());
    for (const ClipperLib::IntPoint& p : path)
        loop.emplace_back(static_cast<double>(p.X) / units_per_mm,
                          static_cast<double>(p.Y) / units_per_mm);
    return loop;
}

// Even-odd union: nesting decides outer or hole; Clipper returns outer loops with positive
// orientation (counter-clockwise with y up) and holes negative.
ClipperLib::Paths normalised(const std::vector<Polygon>& loops) {
    ClipperLib::Clipper clipper;
    clipper.AddPaths(to_clipper(loops), ClipperLib::ptSubject, true);
    ClipperLib::Paths result;
    clipper.Execute(ClipperLib::ctUnion, result, ClipperLib::pftEvenOdd, ClipperLib::pftEvenOdd);
    return result;
}

void collect_islands(const ClipperLib::PolyNode& node, std::vector<std::vector<Polygon>>& out) {
    for (const ClipperLib::PolyNode* outer : node.Childs) {
        std::vector<Polygon> island{from_clipper(outer->Contour)};
        for (const ClipperLib::PolyNode* hole : outer->Childs)
            island.push_back(from_clipper(hole->Contour));
        out.push_back(std::move(island));
        for (const ClipperLib::PolyNode* hole : outer->Childs) collect_islands(*hole, out);
    }
}

}  // namespace

std::vector<Polygon> offset_region(const std::vector<Polygon>& loops, double delta_mm,
                                   const OffsetOptions& options) {
    if (!(options.arc_tolerance_mm > 0))
        throw std::invalid_argument("offset arc_tolerance_mm must be positive");
    if (!std::isfinite(delta_mm)) throw std::invalid_argument("offset delta_mm must be finite");
    ClipperLib::ClipperOffset offset(2.0, options.arc_tolerance_mm * units_per_mm);
    offset.AddPaths(normalised(loops), ClipperLib::jtRound, ClipperLib::etClosedPolygon);
    ClipperLib::Paths result;
    offset.Execute(result, delta_mm * units_per_mm);
    std::vector<Polygon> out;
    out.reserve(result.size());
    for (const ClipperLib::Path& path : result) out.push_back(from_clipper(path));
    return out;
}

std::vector<std::vector<Polygon>> split_islands(const std::vector<Polygon>& loops) {
    ClipperLib::Clipper clipper;
    clipper.AddPaths(to_clipper(loops), ClipperLib::ptSubject, true);
    ClipperLib::PolyTree tree;
    clipper.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftEvenOdd, ClipperLib::pftEvenOdd);
    std::vector<std::vector<Polygon>> islands;
    collect_islands(tree, islands);
    return islands;
}

}  // namespace fibrecell::planner
