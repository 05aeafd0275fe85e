#include "planner/fea/nodal_loads.hpp"

namespace fibrecell::planner {

std::vector<Eigen::Vector3d> nodal_forces(const TetMesh& mesh,
                                          const std::vector<ForceRegion>& loads) {
    std::vector<Eigen::Vector3d> f(mesh.vertex_count(), Eigen::Vector3d::Zero());
    for (const ForceRegion& load : loads) {
        double area = 0;
        for (const BoundaryTriangle& t : load.triangles) area += triangle_area(mesh, t);
        const Eigen::Vector3d traction = load.total_force_n / area;  // [N/mm^2]
        for (const BoundaryTriangle& t : load.triangles) {
            const Eigen::Vector3d share = traction * (triangle_area(mesh, t) / 3.0);
            for (int v : t.v) f[v] += share;
        }
    }
    return f;
}

}  // namespace fibrecell::planner
