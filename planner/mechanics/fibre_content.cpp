#include "planner/mechanics/fibre_content.hpp"

#include "planner/fea/tet_element.hpp"
#include "planner/layers/triangle_locator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fibrecell::planner {
namespace {

// Median triangle edge of a section: the locator's grid cell.
double typical_edge_mm(const LayerMesh& section) {
    std::vector<double> edges;
    edges.reserve(section.triangles.size());
    for (const auto& t : section.triangles)
        edges.push_back((section.vertices[t[1]] - section.vertices[t[0]]).norm());
    if (edges.empty()) return 1.0;
    std::nth_element(edges.begin(), edges.begin() + edges.size() / 2, edges.end());
    return std::max(edges[edges.size() / 2], 1e-3);
}

VoigtVector voigt_direction(const Eigen::Vector3d& t) {
    VoigtVector m;
    m << t.x() * t.x(), t.y() * t.y(), t.z() * t.z(), t.y() * t.z(), t.x() * t.z(), t.x() * t.y();
    return m;
}

}  // namespace

FibreContent fibre_content(const TetMesh& model_mesh, const Placement& placement,
                           const std::vector<ToolpathLayer>& layers,
                           const std::vector<LayerMesh>& sections,
                           const FibreContentOptions& options) {
    if (layers.size() != sections.size())
        throw std::invalid_argument("fibre content: " + std::to_string(layers.size()) +
                                    " layers but " + std::to_string(sections.size()) + " sections");
    const std::size_t tets = model_mesh.tet_count();
    FibreContent c;
    c.length_mm.assign(tets, 0.0);
    c.tangents.assign(tets, Eigen::Matrix3d::Zero());
    c.orientation4.assign(tets, VoigtStiffness::Zero());
    // A bed-frame direction in the model frame: p_bed = R p_model + t.
    const Eigen::Matrix3d to_model = placement.rotation.transpose();

    for (std::size_t i = 0; i < layers.size(); ++i) {
        if (layers[i].head != Head::ccf || layers[i].paths.empty()) continue;
        const LayerMesh& section = sections[i];
        const TriangleLocator locator(section, typical_edge_mm(section));
        auto add_segment = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
            const double length = (b - a).norm();
            if (length <= 0) return;
            const Eigen::Vector3d t =
                (to_model * Eigen::Vector3d((b - a).x(), (b - a).y(), 0)).normalized();
            const Eigen::Matrix3d tt = t * t.transpose();
            const VoigtVector m = voigt_direction(t);
            const VoigtStiffness mm = m * m.transpose();
            const int pieces = std::max(1, static_cast<int>(std::ceil(length / options.step_mm)));
            const double piece = length / pieces;
            for (int k = 0; k < pieces; ++k) {
                const Eigen::Vector2d mid = a + (b - a) * ((k + 0.5) / pieces);
                const int f = locator.locate(mid);
                if (f < 0) {
                    c.unplaced_mm += piece;
                    continue;
                }
                const auto tet = static_cast<std::size_t>(section.triangle_tet[f]);
                c.length_mm[tet] += piece;
                c.tangents[tet] += piece * tt;
                c.orientation4[tet] += piece * mm;
                c.placed_mm += piece;
            }
        };
        for (const Toolpath& p : layers[i].paths) {
            for (std::size_t k = 1; k < p.points.size(); ++k)
                add_segment(p.points[k - 1], p.points[k]);
            if (p.closed && p.points.size() > 2) add_segment(p.points.back(), p.points.front());
        }
    }
    return c;
}

}  // namespace fibrecell::planner
