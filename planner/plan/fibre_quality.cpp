#include "planner/plan/fibre_quality.hpp"

#include "planner/layers/triangle_locator.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>

namespace fibrecell::planner {

FibreQualitySums& FibreQualitySums::operator+=(const FibreQualitySums& o) {
    weighted_cos += o.weighted_cos;
    weight += o.weight;
    density.insert(density.end(), o.density.begin(), o.density.end());
    stress_p.insert(stress_p.end(), o.stress_p.begin(), o.stress_p.end());
    turning_rad += o.turning_rad;
    turned_length_mm += o.turned_length_mm;
    return *this;
}

double FibreQualitySums::turning_deg_per_m() const {
    return turned_length_mm > 0 ? turning_rad * 180.0 / std::numbers::pi / (turned_length_mm / 1e3)
                                : 0.0;
}

namespace {

// Points every `chord` mm of arc length along a path (a closed one back to its start).
std::vector<Eigen::Vector2d> arc_samples(const Toolpath& path, double chord) {
    std::vector<Eigen::Vector2d> out;
    const std::size_t n = path.points.size();
    if (n < 2) return out;
    out.push_back(path.points.front());
    double carried = 0;  // arc length since the last sample
    for (std::size_t i = 0; i + 1 < n + (path.closed ? 1 : 0); ++i) {
        const Eigen::Vector2d a = path.points[i], b = path.points[(i + 1) % n];
        const double len = (b - a).norm();
        double at = chord - carried;
        for (; at <= len; at += chord) out.push_back(a + (b - a) * (at / len));
        carried = len - (at - chord);
    }
    return out;
}

// The absolute heading change between successive chords, over the length they cover.
void add_turning(FibreQualitySums& sums, const Toolpath& path, double chord) {
    const std::vector<Eigen::Vector2d> s = arc_samples(path, chord);
    const std::size_t chords = s.size() < 2 ? 0 : s.size() - 1;
    for (std::size_t i = 1; i < chords; ++i) {
        const Eigen::Vector2d u = s[i] - s[i - 1], v = s[i + 1] - s[i];
        sums.turning_rad += std::abs(std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v)));
    }
    sums.turned_length_mm += static_cast<double>(chords) * chord;
}

}  // namespace

double FibreQualitySums::density_correlation() const {
    const std::size_t n = density.size();
    if (n < 3) return 0.0;
    double mx = 0, my = 0;
    for (std::size_t i = 0; i < n; ++i) mx += density[i], my += stress_p[i];
    mx /= n, my /= n;
    double sxy = 0, sxx = 0, syy = 0;
    for (std::size_t i = 0; i < n; ++i) {
        sxy += (density[i] - mx) * (stress_p[i] - my);
        sxx += (density[i] - mx) * (density[i] - mx);
        syy += (stress_p[i] - my) * (stress_p[i] - my);
    }
    return sxx > 0 && syy > 0 ? sxy / std::sqrt(sxx * syy) : 0.0;
}

FibreQualitySums fibre_quality(const LayerMesh& layer, const std::vector<Toolpath>& paths,
                               const std::vector<Eigen::Vector3d>& v_e,
                               const std::vector<double>& sigma_e,
                               const std::vector<std::uint8_t>& v_defined,
                               const FibreQualityOptions& options) {
    FibreQualitySums sums;
    if (layer.triangles.empty()) return sums;
    const TriangleLocator locate(layer, 2.0);
    const double c = options.cell_mm;
    auto cell_of = [&](const Eigen::Vector2d& p) {
        return (static_cast<long long>(std::lround(std::floor(p.x() / c))) << 32) ^
               (std::lround(std::floor(p.y() / c)) & 0xffffffffLL);
    };
    struct Cell {
        double area = 0, stress_area = 0, fibre = 0;
    };
    std::unordered_map<long long, Cell> cells;
    for (std::size_t f = 0; f < layer.triangles.size(); ++f) {
        const auto& t = layer.triangles[f];
        const Eigen::Vector2d a = layer.vertices[t[0]], b = layer.vertices[t[1]],
                              d = layer.vertices[t[2]];
        const double area = 0.5 * std::abs((b - a).x() * (d - a).y() - (b - a).y() * (d - a).x());
        Cell& cell = cells[cell_of((a + b + d) / 3.0)];
        cell.area += area;
        cell.stress_area +=
            area * std::pow(std::max(sigma_e[layer.triangle_tet[f]], 0.0), options.p);
    }
    for (const Toolpath& path : paths) {
        add_turning(sums, path, options.turning_chord_mm);
        const std::size_t n = path.points.size();
        for (std::size_t i = 0; i + 1 < n + (path.closed ? 1 : 0); ++i) {
            const Eigen::Vector2d a = path.points[i], b = path.points[(i + 1) % n];
            const double len = (b - a).norm();
            if (len <= 0) continue;
            const Eigen::Vector2d mid = 0.5 * (a + b);
            if (auto it = cells.find(cell_of(mid)); it != cells.end()) it->second.fibre += len;
            const int f = locate.locate(mid);
            if (f < 0) continue;
            const int tet = layer.triangle_tet[f];
            const Eigen::Vector2d v = v_e[tet].head<2>();
            if (!v_defined[tet] || v.norm() < 1e-9) continue;
            const double w = std::max(sigma_e[tet], 0.0) * len;
            sums.weighted_cos += w * std::abs((b - a).dot(v) / (len * v.norm()));
            sums.weight += w;
        }
    }
    // Only cells mostly inside the part: partial cells at the outline would skew the density.
    for (const auto& [_, cell] : cells) {
        if (cell.area < 0.5 * c * c) continue;
        sums.density.push_back(cell.fibre / cell.area);
        sums.stress_p.push_back(cell.stress_area / cell.area);
    }
    return sums;
}

}  // namespace fibrecell::planner
