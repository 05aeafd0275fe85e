#include "planner/fea/load_case_check.hpp"

#include "planner/fea/fea_error.hpp"
#include "planner/fea/mesh_parts.hpp"

#include <cmath>
#include <sstream>

namespace fibrecell::planner {
namespace {

constexpr int kPartsListed = 5;  // longer lists bury the message

std::string number_text(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
}

std::string point_text(const Eigen::Vector3d& p) {
    std::ostringstream s;
    s << '[' << p.x() << ", " << p.y() << ", " << p.z() << ']';
    return s.str();
}

void check_material(const Material& m) {
    if (!(m.youngs_modulus_mpa > 0) || !std::isfinite(m.youngs_modulus_mpa))
        throw FeaError("Young's modulus must be positive and finite, got " +
                       number_text(m.youngs_modulus_mpa) + " MPa");
    if (!(m.poisson_ratio > -1 && m.poisson_ratio < 0.5))
        throw FeaError("Poisson's ratio must lie in (-1, 0.5), got " +
                       number_text(m.poisson_ratio));
}

// The added stiffness must be one symmetric, finite matrix per tet, or none. (Positive
// semi-definiteness is the maker's: an eigen-solve per tet would cost more than the assembly.)
void check_added_stiffness(const TetMesh& mesh, const std::vector<VoigtStiffness>& added) {
    if (added.empty()) return;
    if (added.size() != mesh.tet_count())
        throw FeaError("the added stiffness has " + std::to_string(added.size()) +
                       " entries for a mesh of " + std::to_string(mesh.tet_count()) + " tets");
    for (std::size_t t = 0; t < added.size(); ++t) {
        const VoigtStiffness& c = added[t];
        const double scale = c.cwiseAbs().maxCoeff();
        if (!std::isfinite(scale) || (c - c.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale)
            throw FeaError("the added stiffness of tet " + std::to_string(t) +
                           " is not symmetric and finite");
    }
}

void check_vertex_index(const TetMesh& mesh, int v, const std::string& what) {
    if (v < 0 || static_cast<std::size_t>(v) >= mesh.vertex_count())
        throw FeaError(what + " refers to vertex " + std::to_string(v) + " but the mesh has " +
                       std::to_string(mesh.vertex_count()) + " vertices");
}

void check_tets(const TetMesh& mesh) {
    if (mesh.tets.empty()) throw FeaError("the mesh has no tetrahedra");
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
        for (int v : mesh.tets[t]) check_vertex_index(mesh, v, "tet " + std::to_string(t));
        const double volume = signed_volume(mesh, mesh.tets[t]);
        if (!(volume > 0))
            throw FeaError("tet " + std::to_string(t) + " is inverted or flat (volume " +
                           number_text(volume) + " mm^3)");
    }
}

void check_loads(const TetMesh& mesh, const LoadCase& load_case,
                 const std::vector<std::uint8_t>& used) {
    for (const ForceRegion& load : load_case.loads) {
        const std::string what = "load region '" + load.name + "'";
        if (load.triangles.empty()) throw FeaError(what + " has no triangles");
        if (!load.total_force_n.allFinite()) throw FeaError(what + " has a non-finite force");
        double area = 0;
        for (const BoundaryTriangle& t : load.triangles) {
            for (int v : t.v) {
                check_vertex_index(mesh, v, what);
                if (!used[v])
                    throw FeaError(what + " uses vertex " + std::to_string(v) +
                                   ", which belongs to no tet");
            }
            area += triangle_area(mesh, t);
        }
        if (!(area > 0)) throw FeaError(what + " has zero area");
    }
}

// Used vertices held by some support.
std::vector<std::uint8_t> fixed_vertices(const TetMesh& mesh, const LoadCase& load_case,
                                         const std::vector<std::uint8_t>& used) {
    if (load_case.supports.empty())
        throw FeaError("no supports: the part can move freely; fix at least one region");
    std::vector<std::uint8_t> fixed(mesh.vertex_count(), 0);
    for (const FixedRegion& support : load_case.supports) {
        const std::string what = "support region '" + support.name + "'";
        if (support.vertices.empty()) throw FeaError(what + " has no vertices");
        for (int v : support.vertices) {
            check_vertex_index(mesh, v, what);
            if (used[v]) fixed[v] = 1;
        }
    }
    return fixed;
}

struct PartSummary {
    std::size_t vertex_count = 0;
    Box box;
    std::vector<int> fixed;  // fixed vertex indices
};

std::string part_text(int index, const PartSummary& p) {
    return "part " + std::to_string(index + 1) + " (" + std::to_string(p.vertex_count) +
           " vertices, box " + point_text(p.box.min) + "-" + point_text(p.box.max) + " mm)";
}

// A part held only at points of one line can still rotate about that line.
void check_not_collinear(const TetMesh& mesh, int index, const PartSummary& p) {
    const double tol = 1e-9 * (p.box.max - p.box.min).norm();
    const Eigen::Vector3d& a = mesh.vertices[p.fixed.front()];
    int far = p.fixed.front();
    for (int v : p.fixed)
        if ((mesh.vertices[v] - a).norm() > (mesh.vertices[far] - a).norm()) far = v;
    const Eigen::Vector3d axis = mesh.vertices[far] - a;
    const std::string count =
        std::to_string(p.fixed.size()) + " fixed vert" + (p.fixed.size() == 1 ? "ex" : "ices");
    if (axis.norm() <= tol)
        throw FeaError(part_text(index, p) + " is held at one point only, " + point_text(a) + " (" +
                       count + "), so it can rotate about it; fix three points not on one line");
    const Eigen::Vector3d dir = axis.normalized();
    for (int v : p.fixed) {
        const Eigen::Vector3d d = mesh.vertices[v] - a;
        if ((d - d.dot(dir) * dir).norm() > tol) return;
    }
    throw FeaError("the fixed vertices of " + part_text(index, p) + " all lie on one line (" +
                   count + " from " + point_text(a) + " to " + point_text(mesh.vertices[far]) +
                   "), so the part can rotate about it; fix a vertex off that line");
}

void check_parts_supported(const TetMesh& mesh, const std::vector<std::uint8_t>& fixed) {
    const MeshParts parts = mesh_parts(mesh);
    std::vector<PartSummary> summary(parts.count);
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        const int part = parts.part_of_vertex[v];
        if (part < 0) continue;
        PartSummary& p = summary[part];
        ++p.vertex_count;
        p.box.add(mesh.vertices[v]);
        if (fixed[v]) p.fixed.push_back(static_cast<int>(v));
    }
    std::vector<int> floating;
    for (int i = 0; i < parts.count; ++i)
        if (summary[i].fixed.empty()) floating.push_back(i);
    if (parts.count == 1 && !floating.empty())
        throw FeaError(
            "no support holds a vertex of the mesh (their vertices belong to no tet), "
            "so it can move freely: " +
            part_text(0, summary[0]));
    if (!floating.empty()) {
        std::string msg = "the mesh has " + std::to_string(parts.count) + " connected parts and " +
                          std::to_string(floating.size()) + " of them " +
                          (floating.size() == 1 ? "has" : "have") +
                          " no fixed vertex, so it can move freely: ";
        for (std::size_t i = 0; i < floating.size() && i < kPartsListed; ++i)
            msg += (i ? "; " : "") + part_text(floating[i], summary[floating[i]]);
        if (floating.size() > kPartsListed)
            msg += "; and " + std::to_string(floating.size() - kPartsListed) + " more";
        throw FeaError(msg);
    }
    for (int i = 0; i < parts.count; ++i) check_not_collinear(mesh, i, summary[i]);
}

}  // namespace

VertexRoles check_load_case(const TetMesh& mesh, const LoadCase& load_case) {
    check_material(load_case.material);
    check_tets(mesh);
    check_added_stiffness(mesh, load_case.added_stiffness);
    VertexRoles roles;
    roles.used.assign(mesh.vertex_count(), 0);
    for (const Tet& t : mesh.tets)
        for (int v : t) roles.used[v] = 1;
    roles.fixed = fixed_vertices(mesh, load_case, roles.used);
    check_loads(mesh, load_case, roles.used);
    check_parts_supported(mesh, roles.fixed);
    return roles;
}

}  // namespace fibrecell::planner
