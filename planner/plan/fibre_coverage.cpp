#include "planner/plan/fibre_coverage.hpp"

#include "planner/toolpaths/path_order.hpp"
#include "planner/toolpaths/polygon_offset.hpp"

namespace fibrecell::planner {
namespace {

std::vector<Polygon> ribbons(const std::vector<Toolpath>& paths, double w) {
    std::vector<RibbonLine> lines;
    lines.reserve(paths.size());
    for (const Toolpath& p : paths) lines.push_back({&p.points, p.closed});
    return ribbon_band(lines, w / 2);
}

std::vector<Polygon> region_of(const LayerOutline& outline, double w) {
    return outline.loops.empty() ? std::vector<Polygon>{} : offset_region(outline.loops, -w / 2);
}

}  // namespace

FibreCoverage& FibreCoverage::operator+=(const FibreCoverage& o) {
    if (o.ribbon_mm > 0) ribbon_mm = o.ribbon_mm;
    region_mm2 += o.region_mm2;
    fibre_mm += o.fibre_mm;
    covered_mm2 += o.covered_mm2;
    return *this;
}

FibreCoverage fibre_coverage(const LayerOutline& outline, const std::vector<Toolpath>& paths,
                             double w) {
    FibreCoverage c{.ribbon_mm = w};
    const std::vector<Polygon> region = region_of(outline, w);
    c.region_mm2 = region_area(region);
    for (const Toolpath& p : paths) c.fibre_mm += path_length(p);
    if (c.fibre_mm > 0) c.covered_mm2 = region_area(region_intersection(ribbons(paths, w), region));
    return c;
}

std::vector<Polygon> uncovered_region(const LayerOutline& outline,
                                      const std::vector<Toolpath>& paths, double w) {
    const std::vector<Polygon> region = region_of(outline, w);
    return paths.empty() ? region : region_difference(region, ribbons(paths, w));
}

}  // namespace fibrecell::planner
