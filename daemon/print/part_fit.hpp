#pragma once
// Before any grid, slice or toolpath work, a job's part is checked against the cell that will
// print it: placed as the job says, it must be within the cell's part_limits (size, layers) and
// within the robot's reach for both nozzles. A file of a few bytes can describe a part a
// kilometre wide; planning it would take the machine's memory (docs/service.md, "Size limits").

#include "daemon/cell/cell_config.hpp"
#include "planner/job/job_spec.hpp"
#include "planner/mesh/tet_mesh.hpp"

#include <stdexcept>

namespace fibrecell::daemon::print {

class PartDoesNotFit : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Throws PartDoesNotFit with the figures ("the part as placed is 1000000.0 x 1000000.0 x
// 816496.6 mm; this cell takes at most 400 x 400 x 300 mm (part_limits.max_size_mm)").
void check_part_fits_cell(const planner::TetMesh& mesh, const planner::JobSpec& job,
                          const CellConfig& cell);

}  // namespace fibrecell::daemon::print
