#include "planner/toolpaths/polygon_offset.hpp"

#include "planner/fibre/polyline_resample.hpp"

#include <polyclipping/clipper.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
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

ClipperLib::IntPoint to_units(const Eigen::Vector2d& p) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()))
        throw std::invalid_argument("a point has a non-finite coordinate");
    return {std::llround(p.x() * units_per_mm), std::llround(p.y() * units_per_mm)};
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

std::vector<Polygon> from_clipper(const ClipperLib::Paths& paths) {
    std::vector<Polygon> out;
    out.reserve(paths.size());
    for (const ClipperLib::Path& path : paths) out.push_back(from_clipper(path));
    return out;
}

// Arc-length position [mm] along `line` of the point nearest p.
double arc_position(const std::vector<Eigen::Vector2d>& line, const Eigen::Vector2d& p) {
    double best = std::numeric_limits<double>::infinity(), at = 0, arc = 0;
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
        const Eigen::Vector2d ab = line[i + 1] - line[i];
        const double len2 = ab.squaredNorm();
        const double t = len2 > 0 ? std::clamp((p - line[i]).dot(ab) / len2, 0.0, 1.0) : 0.0;
        const double d = (line[i] + t * ab - p).squaredNorm();
        const double len = std::sqrt(len2);
        if (d < best) {
            best = d;
            at = arc + t * len;
        }
        arc += len;
    }
    return at;
}

// The runs of an open polyline inside the region, ordered and directed along it.
std::vector<std::vector<Eigen::Vector2d>> clip_open(const ClipperLib::Paths& region,
                                                    const std::vector<Eigen::Vector2d>& line) {
    ClipperLib::Path subject;
    subject.reserve(line.size());
    for (const Eigen::Vector2d& p : line) subject.push_back(to_units(p));
    ClipperLib::Clipper clipper;
    clipper.AddPath(subject, ClipperLib::ptSubject, false);
    clipper.AddPaths(region, ClipperLib::ptClip, true);
    ClipperLib::PolyTree tree;
    clipper.Execute(ClipperLib::ctIntersection, tree, ClipperLib::pftEvenOdd,
                    ClipperLib::pftEvenOdd);
    ClipperLib::Paths open;
    ClipperLib::OpenPathsFromPolyTree(tree, open);
    // Clipper does not promise the input's order or direction: restore both from where each
    // run lies along the line.
    std::vector<std::pair<double, std::vector<Eigen::Vector2d>>> runs;
    for (const ClipperLib::Path& path : open) {
        if (path.size() < 2) continue;
        Polygon run = from_clipper(path);
        double first = arc_position(line, run.front()), last = arc_position(line, run.back());
        if (last < first) {
            std::reverse(run.begin(), run.end());
            std::swap(first, last);
        }
        runs.emplace_back(first, std::move(run));
    }
    std::sort(runs.begin(), runs.end(),
              [](const auto& x, const auto& y) { return x.first < y.first; });
    std::vector<std::vector<Eigen::Vector2d>> out;
    for (auto& r : runs) out.push_back(std::move(r.second));
    return out;
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

std::vector<Polygon> segment_band(const std::vector<Segment2>& segments, double radius_mm,
                                  const OffsetOptions& options) {
    if (!(radius_mm > 0) || !std::isfinite(radius_mm))
        throw std::invalid_argument("band radius_mm must be positive");
    if (!(options.arc_tolerance_mm > 0))
        throw std::invalid_argument("offset arc_tolerance_mm must be positive");
    ClipperLib::ClipperOffset offset(2.0, options.arc_tolerance_mm * units_per_mm);
    for (const Segment2& s : segments)
        offset.AddPath({to_units(s[0]), to_units(s[1])}, ClipperLib::jtRound,
                       ClipperLib::etOpenRound);
    ClipperLib::Paths result;
    offset.Execute(result, radius_mm * units_per_mm);
    return from_clipper(result);
}

std::vector<Polygon> line_band(const std::vector<std::vector<Eigen::Vector2d>>& lines,
                               double radius_mm, const OffsetOptions& options) {
    if (!(radius_mm > 0) || !std::isfinite(radius_mm))
        throw std::invalid_argument("band radius_mm must be positive");
    if (!(options.arc_tolerance_mm > 0))
        throw std::invalid_argument("offset arc_tolerance_mm must be positive");
    ClipperLib::ClipperOffset offset(2.0, options.arc_tolerance_mm * units_per_mm);
    for (const std::vector<Eigen::Vector2d>& line : lines) {
        if (line.empty()) continue;
        ClipperLib::Path path;
        path.reserve(line.size());
        for (const Eigen::Vector2d& p : line) path.push_back(to_units(p));
        offset.AddPath(path, ClipperLib::jtRound, ClipperLib::etOpenRound);
    }
    ClipperLib::Paths result;
    offset.Execute(result, radius_mm * units_per_mm);
    return from_clipper(result);
}

std::vector<Polygon> region_difference(const std::vector<Polygon>& a,
                                       const std::vector<Polygon>& b) {
    ClipperLib::Clipper clipper;
    clipper.AddPaths(to_clipper(a), ClipperLib::ptSubject, true);
    if (!b.empty()) clipper.AddPaths(to_clipper(b), ClipperLib::ptClip, true);
    ClipperLib::Paths result;
    clipper.Execute(ClipperLib::ctDifference, result, ClipperLib::pftEvenOdd,
                    ClipperLib::pftNonZero);
    return from_clipper(result);
}

double region_area(const std::vector<Polygon>& loops) {
    if (loops.empty()) return 0;
    double area = 0;  // outer loops counter-clockwise (positive), holes clockwise (negative)
    for (const ClipperLib::Path& path : normalised(loops)) area += ClipperLib::Area(path);
    return area / (units_per_mm * units_per_mm);
}

bool inside_region(const std::vector<Polygon>& region, const Eigen::Vector2d& p) {
    // Even-odd by crossings of a ray to +x (each edge counts for y in [lo, hi)): no copy of the
    // region, so a caller may test many points against a large one.
    bool inside = false;
    for (const Polygon& loop : region) {
        const std::size_t n = loop.size();
        for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
            const Eigen::Vector2d& a = loop[i];
            const Eigen::Vector2d& b = loop[j];
            if ((a.y() > p.y()) == (b.y() > p.y())) continue;
            const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
            if (p.x() < x) inside = !inside;
        }
    }
    return inside;
}

ClippedRuns clip_polyline(const std::vector<Polygon>& region,
                          const std::vector<Eigen::Vector2d>& line, bool closed) {
    ClippedRuns out;
    if (line.size() < 2 || region.empty()) return out;
    const ClipperLib::Paths clip = to_clipper(region);
    if (!closed) {
        out.runs = clip_open(clip, line);
        return out;
    }
    // A closed line is clipped as an open one that starts outside, so that no run wraps round
    // its start; wholly inside, it stays closed.
    std::vector<Eigen::Vector2d> ring = line;
    const auto outside = std::find_if(ring.begin(), ring.end(), [&](const Eigen::Vector2d& p) {
        return !inside_region(region, p);
    });
    if (outside != ring.end()) {
        std::rotate(ring.begin(), outside, ring.end());
        ring.push_back(ring.front());
        out.runs = clip_open(clip, ring);
        return out;
    }
    ring.push_back(ring.front());
    std::vector<std::vector<Eigen::Vector2d>> runs = clip_open(clip, ring);
    if (runs.size() == 1 && (runs[0].front() - runs[0].back()).norm() < 1e-4) {
        runs[0].pop_back();
        out.runs = std::move(runs);
        out.closed_inside = true;
        return out;
    }
    // Every vertex inside, yet it leaves the region between two of them: start where a run
    // starts (it enters the region there) and clip again.
    if (runs.empty()) return out;
    const Eigen::Vector2d entry = runs.front().front();
    const double at = arc_position(ring, entry);
    std::vector<Eigen::Vector2d> from_entry{entry}, before;
    double arc = 0;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
        if (i > 0) arc += (ring[i] - ring[i - 1]).norm();
        (arc > at ? from_entry : before).push_back(ring[i]);
    }
    from_entry.insert(from_entry.end(), before.begin(), before.end());
    from_entry.push_back(entry);
    out.runs = clip_open(clip, from_entry);
    return out;
}

namespace {

// How near [mm] a line may come to a region's edge and still be taken as wholly on one side of
// it without Clipper (whose rounding is 1e-5 mm).
constexpr double clear_of_edge_mm = 1e-6;

// RegionClip's grid of the outline's edges: its cell, and the longest piece an edge is cut into,
// so that a long edge sits in a few cells, not in every cell of its bounding box.
constexpr double outline_cell_mm = 2.0;

}  // namespace

RegionClip::RegionClip(std::vector<Polygon> region)
    : region_(std::move(region)), outline_(outline_cell_mm) {
    to_clipper(region_);  // the same errors for a bad region as clip_polyline's
    for (std::size_t i = 0; i < region_.size(); ++i)
        outline_.insert_polyline(resampled(region_[i], true, outline_cell_mm), true,
                                 static_cast<int>(i));
}

bool RegionClip::meets_outline(const std::vector<Eigen::Vector2d>& line, bool closed) const {
    const std::size_t n = line.size();
    const std::size_t segments = closed && n > 2 ? n : n - 1;
    bool meets = false;
    for (std::size_t i = 0; i < segments && !meets; ++i) {
        const Eigen::Vector2d& a = line[i];
        const Eigen::Vector2d& b = line[(i + 1) % n];
        outline_.around_box(a.cwiseMin(b), a.cwiseMax(b), [&](const TaggedSegment& edge) {
            meets = meets || segment_distance(a, b, edge.a, edge.b) <= clear_of_edge_mm;
        });
    }
    return meets;
}

bool RegionClip::holds_segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
    if ((b - a).norm() <= 1e-4) return true;  // within the tolerance below, whatever it crosses
    // Clear of every edge, the segment is wholly on one side: no Clipper run over the region.
    if (!meets_outline({a, b}, false)) return inside_region(region_, a);
    double kept = 0;
    for (const auto& run : clip_polyline(region_, {a, b}, false).runs)
        for (std::size_t i = 1; i < run.size(); ++i) kept += (run[i] - run[i - 1]).norm();
    return kept >= (b - a).norm() - 1e-4;
}

ClippedRuns RegionClip::operator()(const std::vector<Eigen::Vector2d>& line, bool closed) const {
    if (line.size() < 2 || region_.empty() || meets_outline(line, closed))
        return clip_polyline(region_, line, closed);
    ClippedRuns out;
    if (!inside_region(region_, line.front())) return out;
    out.runs.push_back(line);
    out.closed_inside = closed;
    return out;
}

}  // namespace fibrecell::planner
