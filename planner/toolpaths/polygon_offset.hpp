#pragma once
// Polygon offsets, island splitting and clipping on top of Clipper 6.4, the one place that knows
// Clipper's integer coordinates (1 unit = 1e-5 mm: a 300 mm bed spans 3e7 units, far inside
// Clipper's 64-bit range, and rounding stays below 1e-5 mm).

#include "planner/fibre/segment_grid.hpp"
#include "planner/layers/layer_mesh.hpp"

#include <array>
#include <vector>

namespace fibrecell::planner {

struct OffsetOptions {
    double arc_tolerance_mm = 0.002;  // largest gap between a round join's chords and its arc
};

// Offsets a region by delta_mm with round joins: > 0 grows it (outer loops move out, holes
// shrink), < 0 shrinks it. `loops` [mm] is read even-odd, so nesting decides outer or hole and
// orientation does not matter. Returns the offset region's loops [mm], outer loops counter-
// clockwise, holes clockwise; empty when the region vanishes. Every returned vertex lies at
// |delta_mm| from the input boundary (up to 1e-5 mm); chords of round joins may cut up to
// 2.25 x arc_tolerance_mm closer (Clipper rounds a short arc's number of chords down). Throws
// std::invalid_argument on a loop with fewer than 3 points or a non-finite coordinate.
std::vector<Polygon> offset_region(const std::vector<Polygon>& loops, double delta_mm,
                                   const OffsetOptions& options = {});

// Splits a region (read even-odd) into islands: each an outer loop (counter-clockwise) followed by
// its holes (clockwise). An island inside a hole of another is its own island. Throws as above.
std::vector<std::vector<Polygon>> split_islands(const std::vector<Polygon>& loops);

// A straight piece of an outline [mm], from [0] to [1].
using Segment2 = std::array<Eigen::Vector2d, 2>;

// The region within radius_mm of any of `segments` (round caps: the union of their capsules), as
// loops read even-odd; empty for no segments. Throws std::invalid_argument on a non-finite
// coordinate or a non-positive radius.
std::vector<Polygon> segment_band(const std::vector<Segment2>& segments, double radius_mm,
                                  const OffsetOptions& options = {});

// The region within radius_mm of any of `lines` [mm] (polylines with round ends; a loop repeats
// its first point at its end), as loops read even-odd; empty for no lines. The same as
// segment_band over their segments, offset a line at a time (far fewer joins to union). Throws
// std::invalid_argument on a non-finite coordinate or a non-positive radius.
std::vector<Polygon> line_band(const std::vector<std::vector<Eigen::Vector2d>>& lines,
                               double radius_mm, const OffsetOptions& options = {});

// Area [mm^2] of a region read even-odd (holes subtract, overlaps do not count twice).
double region_area(const std::vector<Polygon>& loops);

// The region `a` minus the region `b` (both read even-odd), outer loops counter-clockwise.
std::vector<Polygon> region_difference(const std::vector<Polygon>& a,
                                       const std::vector<Polygon>& b);

// p lies strictly inside the region (read even-odd); a point on its edge may go either way.
bool inside_region(const std::vector<Polygon>& region, const Eigen::Vector2d& p);

// The runs of the polyline `line` [mm] inside `region`, in the order and direction they come
// along it; for a closed line the run through its first point is one run. A closed line wholly
// inside comes back as the one run with `closed_inside` set. Points are rounded to 1e-5 mm.
struct ClippedRuns {
    std::vector<std::vector<Eigen::Vector2d>> runs;
    bool closed_inside = false;
};
ClippedRuns clip_polyline(const std::vector<Polygon>& region,
                          const std::vector<Eigen::Vector2d>& line, bool closed);

// clip_polyline for many lines against one region. A line that comes nowhere near the region's
// outline (within 1e-6 mm) is wholly inside, and comes back as it is, or wholly outside: only
// the lines that meet the outline are clipped by Clipper, each against the whole region.
class RegionClip {
  public:
    explicit RegionClip(std::vector<Polygon> region);
    ClippedRuns operator()(const std::vector<Eigen::Vector2d>& line, bool closed) const;

    // The whole segment a-b lies in the region (up to 1e-4 mm of it outside): a chord across a
    // bend of the region's edge does not, though both ends and its middle may be inside.
    bool holds_segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;

  private:
    bool meets_outline(const std::vector<Eigen::Vector2d>& line, bool closed) const;

    std::vector<Polygon> region_;
    SegmentGrid outline_;  // the region's edges in pieces of at most a cell
};

}  // namespace fibrecell::planner
