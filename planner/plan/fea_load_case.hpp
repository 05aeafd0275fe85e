#pragma once
// A job's load case (model.load_case or analysis.load_case) as the FEA takes it: supports fix the
// vertices of the boundary triangles inside their regions, loads spread over the triangles inside
// theirs.

#include "planner/fea/linear_elastic.hpp"
#include "planner/job/job_spec.hpp"
#include "planner/mesh/boundary.hpp"
#include "planner/mesh/tet_mesh.hpp"

#include <vector>

namespace fibrecell::planner {

// boundary: the model's boundary triangles. Throws std::invalid_argument for a region that
// selects no boundary triangle.
LoadCase fea_load_case(const JobSpec& job, const LoadCaseSpec& spec, const VolumeModel& model,
                       const std::vector<BoundaryTriangle>& boundary);

}  // namespace fibrecell::planner
