#include "planner/io/read_model.hpp"

#include "planner/input_error.hpp"
#include "planner/io/msh_reader.hpp"
#include "planner/io/number_parse.hpp"
#include "planner/io/stress_text_reader.hpp"
#include "planner/io/tet_reader.hpp"
#include "planner/io/validate_model.hpp"
#include "planner/io/vtk_reader.hpp"

#include <filesystem>

namespace fibrecell::planner {

VolumeModel read_volume_model(const std::string& mesh_path, const std::string& stress_path) {
    const std::filesystem::path path(mesh_path);
    const std::string extension = path.extension().string();

    if (iequals(extension, ".tet")) {
        const std::filesystem::path selection =
            path.parent_path() / (path.stem().string() + "_selection.txt");
        std::error_code ec;
        return read_tet(mesh_path, stress_path,
                        std::filesystem::is_regular_file(selection, ec) ? selection.string() : "");
    }

    VolumeModel model;
    if (iequals(extension, ".vtk"))
        model = read_vtk(mesh_path);
    else if (iequals(extension, ".msh"))
        model = read_msh(mesh_path);
    else
        throw InputError(
            mesh_path, "",
            "unknown mesh format '" + shown(extension) + "': expected a .vtk, .msh or .tet file");

    if (!stress_path.empty()) {
        model.stress = read_stress_text(stress_path, model.mesh.tet_count());
        validate_stress(model, stress_path);
    }
    return model;
}

}  // namespace fibrecell::planner
