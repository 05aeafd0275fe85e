// A part against the cell's part_limits before any planning work: each limit refuses with the
// figures and the key to change, and a part within all of them passes.
#include "daemon/print/part_fit.hpp"
#include "planner/mesh/structured_mesh.hpp"
#include "tests/support/project_paths.hpp"

#include <gmock/gmock.h>

using namespace fibrecell;
using daemon::print::PartDoesNotFit;
using ::testing::HasSubstr;

namespace {

planner::JobSpec job() {
    return planner::parse_job("name: j\nmodel:\n  mesh: loop.msh\nplacement:\n  position_mm: [150, 150]\n",
                              "j.job.yaml", fibrecell::test::source_path("examples/loop"),
                              planner::JobFiles::anywhere);
}

std::string refusal(const planner::TetMesh& mesh, const daemon::CellConfig& cell) {
    try {
        daemon::print::check_part_fits_cell(mesh, job(), cell);
    } catch (const PartDoesNotFit& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(PartFit, EachLimitRefusesWithItsFiguresAndKey) {
    // 60 x 10 x 1.6 mm in 1,800 tets.
    const auto mesh = planner::structured_tet_mesh({.size = {60, 10, 1.6}, .cells = {30, 5, 2}});
    daemon::CellConfig cell;
    EXPECT_EQ(refusal(mesh, cell), "");
    cell.part_limits.max_tets = 1000;
    EXPECT_THAT(refusal(mesh, cell), HasSubstr("the mesh has 1800 tetrahedra; this cell plans at "
                                               "most 1000 (part_limits.max_tets)"));
    cell.part_limits = {};
    cell.part_limits.max_size_mm = {50, 400, 300};
    EXPECT_THAT(refusal(mesh, cell), HasSubstr("the part as placed is 60.0 x 10.0 x 1.6 mm (x, y, z); "
                                               "this cell takes at most 50 x 400 x 300 mm"));
    cell.part_limits = {};
    cell.part_limits.max_layers = 1;
    EXPECT_THAT(refusal(mesh, cell), HasSubstr("(part_limits.max_layers)"));
}
