#include "planner/mesh/region.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <stdexcept>

namespace fibrecell::planner {
namespace {

struct InsideTest {
    const Eigen::Vector3d& p;
    bool operator()(const BoxRegion& b) const {
        return (p.array() >= b.min.array()).all() && (p.array() <= b.max.array()).all();
    }
    bool operator()(const CylinderRegion& c) const {
        const Eigen::Vector3d d = p - c.point;
        const Eigen::Vector3d radial = d - d.dot(c.axis) * c.axis;
        return std::abs(radial.norm() - c.radius_mm) <= c.tolerance_mm &&
               radial.dot(c.facing) >= -c.tolerance_mm;  // the dividing line belongs to both
    }
    bool operator()(const GroupRegion&) const { return false; }  // handled by vertex list
};

}  // namespace

std::vector<char> vertices_inside(const VolumeModel& model, const Region& region) {
    std::vector<char> inside(model.mesh.vertices.size(), 0);
    if (const auto* g = std::get_if<GroupRegion>(&region.shape)) {
        const auto it = model.vertex_groups.find(g->group);
        if (it == model.vertex_groups.end()) {
            std::string known;
            for (const auto& [name, _] : model.vertex_groups)
                known += (known.empty() ? "" : ", ") + name;
            throw std::invalid_argument("region '" + region.name + "': the mesh has no group '" +
                                        g->group +
                                        "' (groups: " + (known.empty() ? "none" : known) + ")");
        }
        for (int v : it->second) inside[v] = 1;
        return inside;
    }
    for (std::size_t v = 0; v < inside.size(); ++v)
        inside[v] = std::visit(InsideTest{model.mesh.vertices[v]}, region.shape) ? 1 : 0;
    return inside;
}

std::vector<BoundaryTriangle> select_triangles(const VolumeModel& model,
                                               const std::vector<BoundaryTriangle>& boundary,
                                               const Region& region) {
    const std::vector<char> inside = vertices_inside(model, region);
    std::vector<BoundaryTriangle> out;
    for (const auto& t : boundary)
        if (inside[t.v[0]] && inside[t.v[1]] && inside[t.v[2]]) out.push_back(t);
    return out;
}

std::vector<int> triangle_vertices(const std::vector<BoundaryTriangle>& triangles) {
    std::vector<int> out;
    out.reserve(triangles.size() * 3);
    for (const auto& t : triangles) out.insert(out.end(), t.v.begin(), t.v.end());
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

}  // namespace fibrecell::planner
