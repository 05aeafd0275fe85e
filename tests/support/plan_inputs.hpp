#pragma once
// What planner tests set up: model files on disk, and the field stage run on the model a job
// names (the planner itself takes models, not paths: the reading is planner/io's).

#include "config/durable_file.hpp"
#include "planner/io/read_model.hpp"
#include "planner/io/vtk_writer.hpp"
#include "planner/job/job_spec.hpp"
#include "planner/plan/field_stage.hpp"

#include <filesystem>

namespace fibrecell::test {

inline void write_vtk_file(const std::filesystem::path& path, const planner::TetMesh& mesh,
                           const planner::FieldArrays& arrays) {
    config::write_file_durably(path, planner::field_vtk_text(mesh, arrays));
}

inline planner::FieldStageResult field_stage_of(const planner::JobSpec& job) {
    return planner::run_field_stage(
        job, planner::read_volume_model(job.model.mesh_path, job.model.stress_path));
}

}  // namespace fibrecell::test
