#include "planner/plan/fibre_ceiling.hpp"

#include "planner/layers/placement.hpp"

#include <algorithm>
#include <cmath>

namespace fibrecell::planner {

LayerStageResult ideal_fibre_layers(const JobSpec& job, const FieldStageResult& field,
                                    const LayerStageResult& layers) {
    const double w = job.planner.fibre_spacing_mm;
    const std::vector<Eigen::Vector3d> v_placed =
        rotate_vectors(field.field.v_e, placement_for(field.model.mesh, job.placement));
    LayerStageResult out = layers;
    for (std::size_t i = 0; i < out.layers.size(); ++i) {
        ToolpathLayer& layer = out.layers[i];
        if (layer.head != Head::ccf) continue;
        layer.paths.clear();
        const LayerMesh& section = out.sections[i];
        for (std::size_t f = 0; f < section.triangles.size(); ++f) {
            const int tet = section.triangle_tet[f];
            if (!field.v_defined[tet]) continue;
            const Eigen::Vector2d along = v_placed[tet].head<2>();
            if (!(along.norm() > 1e-6)) continue;  // the tension runs across the layer
            const auto& t = section.triangles[f];
            const Eigen::Vector2d a = section.vertices[t[0]], b = section.vertices[t[1]],
                                  c = section.vertices[t[2]];
            const Eigen::Vector2d e1 = b - a, e2 = c - a;
            const double twice_area = std::abs(e1.x() * e2.y() - e1.y() * e2.x());
            if (!(twice_area > 0)) continue;
            // area / W of fibre, in pieces through the centroid short enough to stay inside the
            // triangle (the centroid lies a third of each height from its side), so that all of
            // it is counted in this triangle's tet.
            const double shortest_height =
                twice_area / std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
            const double length = 0.5 * twice_area / w;
            const int pieces = static_cast<int>(std::ceil(length / (2 * shortest_height / 3)));
            const Eigen::Vector2d half = along.normalized() * (length / pieces / 2);
            const Eigen::Vector2d centre = (a + b + c) / 3;
            for (int k = 0; k < pieces; ++k)
                layer.paths.push_back({PathRole::fibre, false, {centre - half, centre + half}});
        }
    }
    return out;
}

}  // namespace fibrecell::planner
