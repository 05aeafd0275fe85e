#include "planner/io/tet_reader.hpp"

#include "planner/io/file_text.hpp"
#include "planner/io/number_parse.hpp"
#include "planner/io/selection_reader.hpp"
#include "planner/io/stress_text_reader.hpp"
#include "planner/io/text_scanner.hpp"
#include "planner/io/validate_model.hpp"

#include <climits>

namespace fibrecell::planner {

TetMesh parse_tet_mesh(std::string_view text, const std::string& file) {
    TextScanner s(text, file);
    // Counts are checked against the file size on their own line, before anything is allocated.
    const long long vertex_count = s.integer("the vertex count", 0, INT_MAX);
    s.check_count(vertex_count, 6, "vertex");  // "x y z" and separators at least
    s.expect("vertices");
    const long long tet_count = s.integer("the tet count", 0, INT_MAX);
    s.check_count(tet_count, 10, "tet");  // "4 a b c d" and separators at least
    s.expect("tets");

    TetMesh mesh;
    mesh.vertices.resize(static_cast<std::size_t>(vertex_count));
    for (Eigen::Vector3d& v : mesh.vertices) {
        v.x() = s.real("a vertex coordinate");
        v.y() = s.real("a vertex coordinate");
        v.z() = s.real("a vertex coordinate");
    }
    mesh.tets.resize(static_cast<std::size_t>(tet_count));
    for (Tet& t : mesh.tets) {
        const long long corners = s.integer("the corner count of a tet (4)");
        if (corners != 4)
            s.fail("a tet line must start with 4 (its corner count), found " +
                   std::to_string(corners));
        for (int& index : t)
            index = static_cast<int>(s.integer("a vertex index", INT_MIN, INT_MAX));
        if (auto problem = tet_index_problem(t, mesh.vertices.size())) s.fail(*problem);
    }
    if (!s.at_end())
        s.fail("unexpected '" + shown(s.token("")) + "' after the last of " +
               std::to_string(tet_count) + " tets (wrong counts in the header?)");
    validate_mesh(mesh, file);
    return mesh;
}

VolumeModel read_tet(const std::string& tet_path, const std::string& stress_path,
                     const std::string& selection_path) {
    VolumeModel model;
    model.mesh = parse_tet_mesh(read_file_text(tet_path), tet_path);
    if (!stress_path.empty()) {
        model.stress = read_stress_text(stress_path, model.mesh.tet_count());
        validate_stress(model, stress_path);
    }
    if (!selection_path.empty()) {
        model.vertex_groups = read_selection(selection_path, model.mesh.vertex_count());
        validate_groups(model, selection_path);
    }
    return model;
}

}  // namespace fibrecell::planner
