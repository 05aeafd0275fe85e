#include "planner/toolpaths/zigzag_fill.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <unordered_map>

namespace fibrecell::planner {
namespace {

// Where a loop edge crosses a scan line. Scan lines are horizontal in the rotated frame; an edge
// (a, b) crosses the line y = c when (a.y > c) != (b.y > c): half-open, so a vertex on a line
// counts once and every loop crosses every line an even number of times.
struct Crossing {
    double x = 0;
    int loop = 0;
    int edge = 0;  // from vertex `edge` to vertex `edge + 1` of the loop
};

struct Segment {
    int line = 0;
    std::array<Crossing, 2> ends;  // left, right
};

struct Link {
    int segment = 0;
    int end = 0;                       // which end of `segment` the link arrives at
    std::vector<Eigen::Vector2d> via;  // boundary vertices between the two ends
};

bool above(const Eigen::Vector2d& p, double c) {
    return p.y() > c;
}

std::int64_t key(int loop, int edge) {
    return (static_cast<std::int64_t>(loop) << 32) | static_cast<std::uint32_t>(edge);
}

class ScanSegments {
  public:
    ScanSegments(std::vector<Polygon> loops, double spacing, double max_link)
        : loops_(std::move(loops)), spacing_(spacing), max_link_(max_link) {
        place_lines();
        for (int j = 0; j < line_count_; ++j) cut_line(j);
    }

    const std::vector<Segment>& segments() const { return segments_; }

    Eigen::Vector2d point(const Crossing& c, int line) const { return {c.x, line_y(line)}; }

    // The link from `end` of `segment` up to a segment end on the next line, if the boundary
    // from there reaches the next line before it returns to this one.
    std::optional<Link> up_link(int segment, int end) const {
        const Segment& s = segments_[static_cast<std::size_t>(segment)];
        const int next = s.line + 1;
        if (next >= line_count_) return std::nullopt;
        const double c = line_y(s.line);
        const double c_up = line_y(next);
        const Crossing& from = s.ends[static_cast<std::size_t>(end)];
        const Polygon& loop = loops_[static_cast<std::size_t>(from.loop)];
        const int n = static_cast<int>(loop.size());
        auto vertex = [&](int i) { return loop[static_cast<std::size_t>((i % n + n) % n)]; };
        auto crosses = [&](int edge, double y) {
            return above(vertex(edge), y) != above(vertex(edge + 1), y);
        };
        const bool forward = above(vertex(from.edge + 1), c);
        Link link;
        Eigen::Vector2d at = point(from, s.line);
        double length = 0;
        int edge = from.edge;
        for (int step = 0; step < n; ++step) {
            if (crosses(edge, c_up)) {
                const auto hit = line_ends_[static_cast<std::size_t>(next)].find(
                    key(from.loop, (edge % n + n) % n));
                if (hit == line_ends_[static_cast<std::size_t>(next)].end()) return std::nullopt;
                const Segment& t = segments_[static_cast<std::size_t>(hit->second.first)];
                const Eigen::Vector2d arrive =
                    point(t.ends[static_cast<std::size_t>(hit->second.second)], next);
                if (length + (arrive - at).norm() > max_link_) return std::nullopt;
                link.segment = hit->second.first;
                link.end = hit->second.second;
                return link;
            }
            if (step > 0 && crosses(edge, c)) return std::nullopt;  // back to this line
            const Eigen::Vector2d corner = forward ? vertex(edge + 1) : vertex(edge);
            length += (corner - at).norm();
            if (length > max_link_) return std::nullopt;
            at = corner;
            link.via.push_back(corner);
            edge += forward ? 1 : -1;
        }
        return std::nullopt;
    }

  private:
    double line_y(int line) const { return first_y_ + line * spacing_; }

    // As many lines as fit strictly inside the extent, centred in it.
    void place_lines() {
        double lo = std::numeric_limits<double>::infinity();
        double hi = -lo;
        for (const Polygon& loop : loops_)
            for (const Eigen::Vector2d& p : loop)
                lo = std::min(lo, p.y()), hi = std::max(hi, p.y());
        if (!(hi > lo)) return;
        const double intervals = std::ceil((hi - lo) / spacing_ - 1e-9);
        if (intervals > 1e7) throw std::invalid_argument("zigzag spacing_mm too small for region");
        line_count_ = std::max(1, static_cast<int>(intervals));
        first_y_ = lo + ((hi - lo) - (line_count_ - 1) * spacing_) / 2;
        line_ends_.resize(static_cast<std::size_t>(line_count_));
    }

    void cut_line(int line) {
        const double c = line_y(line);
        std::vector<Crossing> crossings;
        for (std::size_t l = 0; l < loops_.size(); ++l) {
            const Polygon& loop = loops_[l];
            for (std::size_t e = 0; e < loop.size(); ++e) {
                const Eigen::Vector2d& a = loop[e];
                const Eigen::Vector2d& b = loop[(e + 1) % loop.size()];
                if (above(a, c) == above(b, c)) continue;
                const double x = a.x() + (c - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
                crossings.push_back({x, static_cast<int>(l), static_cast<int>(e)});
            }
        }
        std::sort(crossings.begin(), crossings.end(),
                  [](const Crossing& p, const Crossing& q) { return p.x < q.x; });
        for (std::size_t i = 0; i + 1 < crossings.size(); i += 2) {
            if (crossings[i + 1].x - crossings[i].x < 1e-9) continue;  // touches a vertex only
            const int id = static_cast<int>(segments_.size());
            segments_.push_back({line, {crossings[i], crossings[i + 1]}});
            auto& ends = line_ends_[static_cast<std::size_t>(line)];
            ends[key(crossings[i].loop, crossings[i].edge)] = {id, 0};
            ends[key(crossings[i + 1].loop, crossings[i + 1].edge)] = {id, 1};
        }
    }

    std::vector<Polygon> loops_;
    double spacing_;
    double max_link_;
    int line_count_ = 0;
    double first_y_ = 0;
    std::vector<Segment> segments_;  // by line, then left to right
    // Per line: (loop, edge) of a segment end -> (segment, end).
    std::vector<std::unordered_map<std::int64_t, std::pair<int, int>>> line_ends_;
};

Eigen::Vector2d rotated(const Eigen::Vector2d& p, double cos_a, double sin_a) {
    return {cos_a * p.x() - sin_a * p.y(), sin_a * p.x() + cos_a * p.y()};
}

// Appends p unless it repeats the last point (a link corner on a scan line).
void append(std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& p) {
    if (points.empty() || (points.back() - p).norm() > 1e-9) points.push_back(p);
}

}  // namespace

std::vector<Toolpath> zigzag_fill(const std::vector<Polygon>& region, PathRole role,
                                  const ZigzagOptions& options) {
    if (!(options.spacing_mm > 0) || !std::isfinite(options.spacing_mm))
        throw std::invalid_argument("zigzag spacing_mm must be positive");
    if (!std::isfinite(options.angle_deg))
        throw std::invalid_argument("zigzag angle_deg must be finite");
    if (!(options.max_link_spacings >= 0))
        throw std::invalid_argument("zigzag max_link_spacings must not be negative");

    // Work in a frame where the scan lines are horizontal.
    const double angle = options.angle_deg * std::numbers::pi / 180.0;
    const double cos_a = std::cos(angle);
    const double sin_a = std::sin(angle);
    std::vector<Polygon> loops;
    loops.reserve(region.size());
    for (const Polygon& loop : region) {
        if (loop.size() < 3) continue;  // encloses nothing
        Polygon& r = loops.emplace_back();
        r.reserve(loop.size());
        for (const Eigen::Vector2d& p : loop) r.push_back(rotated(p, cos_a, -sin_a));
    }
    const ScanSegments scan(std::move(loops), options.spacing_mm,
                            options.max_link_spacings * options.spacing_mm);
    const std::vector<Segment>& segments = scan.segments();

    std::vector<Toolpath> paths;
    std::vector<bool> used(segments.size(), false);
    for (std::size_t first = 0; first < segments.size(); ++first) {
        if (used[first]) continue;
        const int s0 = static_cast<int>(first);
        // Leave the first segment by the end that links upwards, preferring the shorter link.
        int exit = 1;
        std::optional<Link> link;
        for (int end : {1, 0}) {
            std::optional<Link> candidate = scan.up_link(s0, end);
            if (!candidate || used[static_cast<std::size_t>(candidate->segment)]) continue;
            if (!link || candidate->via.size() < link->via.size()) {
                link = std::move(candidate);
                exit = end;
            }
        }
        Toolpath path{role, false, {}};
        const Segment* s = &segments[first];
        path.points.push_back(scan.point(s->ends[static_cast<std::size_t>(1 - exit)], s->line));
        path.points.push_back(scan.point(s->ends[static_cast<std::size_t>(exit)], s->line));
        used[first] = true;
        while (link && !used[static_cast<std::size_t>(link->segment)]) {
            const int next = link->segment;
            s = &segments[static_cast<std::size_t>(next)];
            exit = 1 - link->end;
            for (const Eigen::Vector2d& p : link->via) append(path.points, p);
            append(path.points, scan.point(s->ends[static_cast<std::size_t>(link->end)], s->line));
            append(path.points, scan.point(s->ends[static_cast<std::size_t>(exit)], s->line));
            used[static_cast<std::size_t>(next)] = true;
            link = scan.up_link(next, exit);
        }
        for (Eigen::Vector2d& p : path.points) p = rotated(p, cos_a, sin_a);
        paths.push_back(std::move(path));
    }
    return paths;
}

}  // namespace fibrecell::planner
