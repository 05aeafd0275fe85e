#include "planner/io/validate_model.hpp"

#include "planner/input_error.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fibrecell::planner {
namespace {

std::string number_text(double v) {
    std::ostringstream out;
    out.precision(6);
    out << v;
    return out.str();
}

double longest_edge(const TetMesh& mesh, const Tet& t) {
    double longest = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
            longest = std::max(longest, (mesh.vertices[t[i]] - mesh.vertices[t[j]]).norm());
    return longest;
}

}  // namespace

std::string FileNumbering::element_name(std::size_t tet) const {
    const long long n =
        tet < element_numbers.size() ? element_numbers[tet] : first + static_cast<long long>(tet);
    return element + " " + std::to_string(n);
}

std::string FileNumbering::vertex_name(std::size_t v) const {
    const long long n =
        v < vertex_numbers.size() ? vertex_numbers[v] : first + static_cast<long long>(v);
    return vertex + " " + std::to_string(n);
}

std::optional<std::string> tet_index_problem(const Tet& t, std::size_t vertex_count) {
    for (int i = 0; i < 4; ++i) {
        if (t[i] < 0 || static_cast<std::size_t>(t[i]) >= vertex_count)
            return "vertex index " + std::to_string(t[i]) + " is out of range (" +
                   std::to_string(vertex_count) + " vertices, indices from 0)";
        for (int j = 0; j < i; ++j)
            if (t[j] == t[i])
                return "vertex index " + std::to_string(t[i]) + " appears twice in one tet";
    }
    return std::nullopt;
}

void validate_mesh(TetMesh& mesh, const std::string& file, const FileNumbering& numbering) {
    if (mesh.tets.empty()) throw InputError(file, "", "empty mesh: no tetrahedra");
    if (mesh.vertices.empty()) throw InputError(file, "", "empty mesh: no vertices");

    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
        if (!mesh.vertices[v].allFinite())
            throw InputError(file, numbering.vertex_name(v), "coordinate is not a finite number");

    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        if (auto problem = tet_index_problem(mesh.tets[t], mesh.vertices.size()))
            throw InputError(file, numbering.element_name(t), *problem);

    std::size_t inverted = 0;
    std::size_t first_inverted = 0;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const double volume = signed_volume(mesh, mesh.tets[t]);
        const double edge = longest_edge(mesh, mesh.tets[t]);
        // Written so that NaN (from overflowing coordinates) also counts as degenerate.
        if (!(std::abs(volume) >= kDegenerateVolumeRatio * edge * edge * edge))
            throw InputError(file, numbering.element_name(t),
                             "degenerate tet: volume " + number_text(volume) +
                                 " mm^3 is below 1e-9 x (longest edge " + number_text(edge) +
                                 " mm)^3");
        if (volume < 0) {
            if (inverted == 0) first_inverted = t;
            ++inverted;
        }
    }
    if (inverted == mesh.tets.size()) {
        // Some exporters use the opposite convention throughout: adopt ours.
        for (Tet& t : mesh.tets) std::swap(t[2], t[3]);
    } else if (inverted > 0) {
        throw InputError(file, numbering.element_name(first_inverted),
                         "inverted tet (negative volume): " + std::to_string(inverted) + " of " +
                             std::to_string(mesh.tets.size()) +
                             " tets are inverted, the rest positive; orientation must be "
                             "consistent");
    }
}

void validate_stress(VolumeModel& model, const std::string& file, const FileNumbering& numbering) {
    if (!model.stress) return;
    std::vector<StressTensor>& stress = *model.stress;
    if (stress.size() != model.mesh.tets.size())
        throw InputError(file, "",
                         std::to_string(stress.size()) + " stress tensors for " +
                             std::to_string(model.mesh.tets.size()) + " tets");

    double field_max = 0;
    for (std::size_t t = 0; t < stress.size(); ++t) {
        if (!stress[t].allFinite())
            throw InputError(file, numbering.element_name(t), "stress is not a finite number");
        field_max = std::max(field_max, stress[t].cwiseAbs().maxCoeff());
    }
    for (std::size_t t = 0; t < stress.size(); ++t) {
        StressTensor& s = stress[t];
        const double asymmetry = (s - s.transpose()).cwiseAbs().maxCoeff();
        if (asymmetry == 0) continue;
        // Relative to the tensor itself, but not below round-off of the whole field: a near-zero
        // tensor may carry the exporter's absolute noise.
        const double scale = std::max(s.cwiseAbs().maxCoeff(), 1e-6 * field_max);
        if (asymmetry > kAsymmetryTolerance * scale)
            throw InputError(file, numbering.element_name(t),
                             "stress tensor is not symmetric: |s_ij - s_ji| = " +
                                 number_text(asymmetry) + " against largest component " +
                                 number_text(scale) + " (tolerance 1e-3 relative)");
        s = 0.5 * (s + s.transpose()).eval();
    }
}

void validate_groups(VolumeModel& model, const std::string& file) {
    const std::size_t n = model.mesh.vertices.size();
    for (auto& [name, members] : model.vertex_groups) {
        std::sort(members.begin(), members.end());
        members.erase(std::unique(members.begin(), members.end()), members.end());
        if (!members.empty() &&
            (members.front() < 0 || static_cast<std::size_t>(members.back()) >= n))
            throw InputError(
                file, "",
                "vertex group '" + name + "' refers to vertex index " +
                    std::to_string(members.front() < 0 ? members.front() : members.back()) +
                    ", outside the mesh's " + std::to_string(n) + " vertices (indices from 0)");
    }
}

void validate_model(VolumeModel& model, const std::string& file, const FileNumbering& numbering) {
    validate_mesh(model.mesh, file, numbering);
    validate_stress(model, file, numbering);
    validate_groups(model, file);
}

void validate_model(VolumeModel& model, const std::string& file) {
    validate_model(model, file, FileNumbering{});
}

}  // namespace fibrecell::planner
