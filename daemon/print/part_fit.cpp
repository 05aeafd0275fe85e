#include "daemon/print/part_fit.hpp"

#include "drivers/abb/kinematics/joint_solver.hpp"
#include "planner/layers/placement.hpp"

#include <fmt/format.h>

#include <cmath>
#include <optional>

namespace fibrecell::daemon::print {

namespace abb = drivers::abb;

namespace {

// Why the robot cannot put nozzle `n`'s tip at `p` (bed frame) in its print orientation, or
// nullopt. Only "out of reach" counts here: the joint limits and singularities of the real path
// are the robot plan's to check (robot_plan.hpp), on the toolpaths themselves.
std::optional<std::string> out_of_reach(const abb::RobotCellConfig& robot, abb::Nozzle n,
                                        const Eigen::Vector3d& p) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = p;
    pose.linear() = abb::print_orientation(robot.head, n).toRotationMatrix();
    const abb::IkResult r = abb::solve_tcp(robot.model(), robot.frames(n), pose, abb::JointVector{},
                                           robot.solver);
    if (r.failure.kind != abb::IkFailureKind::out_of_reach) return std::nullopt;
    return r.failure.reason;
}

std::string point(const Eigen::Vector3d& p) {
    return fmt::format("({:.1f}, {:.1f}, {:.1f}) mm", p.x(), p.y(), p.z());
}

}  // namespace

void check_part_fits_cell(const planner::TetMesh& mesh, const planner::JobSpec& job,
                          const CellConfig& cell) {
    if (mesh.tet_count() > static_cast<std::size_t>(cell.part_limits.max_tets))
        throw PartDoesNotFit(fmt::format(
            "the mesh has {} tetrahedra; this cell plans at most {} (part_limits.max_tets): "
            "a coarser mesh plans the same part",
            mesh.tet_count(), cell.part_limits.max_tets));
    const planner::Placement placement = planner::placement_for(mesh, job.placement);
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
    for (const Eigen::Vector3d& v : mesh.vertices) {
        const Eigen::Vector3d q = placement.apply(v);
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
    }
    const Eigen::Vector3d size = hi - lo;
    const auto& max = cell.part_limits.max_size_mm;
    if (size.x() > max[0] || size.y() > max[1] || size.z() > max[2])
        throw PartDoesNotFit(fmt::format(
            "the part as placed is {:.1f} x {:.1f} x {:.1f} mm (x, y, z); this cell takes at most "
            "{:g} x {:g} x {:g} mm (part_limits.max_size_mm)",
            size.x(), size.y(), size.z(), max[0], max[1], max[2]));
    const double layer_mm = job.layers.pla_layer_height_mm;
    const double layers = std::ceil(size.z() / layer_mm);
    if (layers > cell.part_limits.max_layers)
        throw PartDoesNotFit(fmt::format(
            "the part is {:.1f} mm high: {:.0f} PLA layers of {:g} mm; this cell takes at most {} "
            "(part_limits.max_layers)",
            size.z(), layers, layer_mm, cell.part_limits.max_layers));

    // The corners of its box first; when one is out of reach, its points decide (a round part's
    // corners are not part of it).
    bool corners_reached = true;
    for (int c = 0; c < 8 && corners_reached; ++c) {
        const Eigen::Vector3d corner((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(),
                                     (c & 4) ? hi.z() : lo.z());
        for (const abb::Nozzle n : {abb::Nozzle::pla, abb::Nozzle::ccf})
            if (out_of_reach(cell.robot, n, corner)) corners_reached = false;
    }
    if (corners_reached) return;
    for (const Eigen::Vector3d& v : mesh.vertices) {
        const Eigen::Vector3d p = placement.apply(v);
        for (const abb::Nozzle n : {abb::Nozzle::pla, abb::Nozzle::ccf})
            if (const auto why = out_of_reach(cell.robot, n, p))
                throw PartDoesNotFit(fmt::format(
                    "the part as placed ({:.1f} x {:.1f} x {:.1f} mm, from {} to {} on the bed) is "
                    "out of the robot's reach: its point {} for the {} nozzle: {}",
                    size.x(), size.y(), size.z(), point(lo), point(hi), point(p),
                    n == abb::Nozzle::pla ? "PLA" : "CCF", *why));
    }
}

}  // namespace fibrecell::daemon::print
