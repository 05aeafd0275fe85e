#pragma once
// End-to-end print tests on the whole simulated cell as the service builds it (SimCellFixture:
// CellDevices with the simulated IRC5 running the real FcMain.mod and the job's chunks, the mock
// GT2560, every driver real), driving a PrintSession that gets the links' events as in the
// service. The expected board log is rebuilt independently from the program and a second
// ExtruderController.
#include "daemon/print/print_session.hpp"
#include "drivers/abb/rapid/rapid_writer.hpp"
#include "drivers/sim/motion/trajectory_analysis.hpp"
#include "../sync/metered_pieces.hpp"
#include "tests/support/eventually.hpp"
#include "tests/support/sim_cell_fixture.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

namespace fibrecell::test {

using namespace std::chrono_literals;
namespace abb = drivers::abb;
using daemon::print::PrintOptions;
using daemon::print::PrintPhase;
using daemon::print::PrintSession;
using drivers::abb::EventKind;

// Simulated seconds per real second. Positions are checked at a lower scale: every real
// millisecond of the service's latency moves the simulated robot `scale` times as far.
constexpr double print_time_scale = 20;
constexpr double pla_speed = 12, ccf_speed = 5;

inline abb::RobotLayer pla_square(int index, double z) {
    abb::RobotLayer pla{.index = index, .z = z, .nozzle = abb::Nozzle::pla};
    pla.paths.push_back(
        {true, {{140, 140}, {160, 140}, {160, 160}, {140, 160}}});
    return pla;
}

// `count` straight fibre paths of `length` mm along x, 10 mm apart.
inline abb::RobotLayer fibre_lines(int index, double z, int count, int length = 100) {
    abb::RobotLayer ccf{.index = index, .z = z, .nozzle = abb::Nozzle::ccf};
    for (int k = 0; k < count; ++k) {
        abb::RobotPath fibre{false, {}};
        for (int i = 0; i <= length / 10; ++i) fibre.points.emplace_back(100 + 10.0 * i, 145 + 10.0 * k);
        ccf.paths.push_back(fibre);
    }
    return ccf;
}

// The sequence of the first event of `kind` (0: none).
inline std::int64_t first_of(const abb::PrintProgram& program, EventKind kind) {
    for (const auto& e : program.events)
        if (e.kind == kind) return e.sequence;
    return 0;
}

inline abb::PrintProgram make_program(const std::vector<abb::RobotLayer>& layers,
                                     double ccf_speed_mm_s = ccf_speed) {
    return abb::build_print_program(layers, abb::RobotCellConfig{},
                                    {.pla_speed_mm_s = pla_speed, .ccf_speed_mm_s = ccf_speed_mm_s,
                                     .cutter_distance_mm = 42});
}

// Every board command of a whole print, in order: the pre-flight heat-up, the engine's start,
// then each event's commands (hotends are hot at every head switch). `first_line`, when given,
// gets the index of each event's first command (by sequence; none: absent).
inline std::vector<std::string> expected_board_log(const abb::PrintProgram& program,
                                                   std::map<int, std::size_t>* first_line = nullptr) {
    drivers::ExtruderController ref{drivers::ExtruderConfig{}};
    const double d = ref.config().filament_diameter_mm;
    const double pla_ratio = 0.8 * 0.8 / (std::numbers::pi * d * d / 4);
    std::vector<std::string> out;
    const auto add = [&](const std::vector<std::string>& lines) {
        out.insert(out.end(), lines.begin(), lines.end());
    };
    add(ref.prepare({}, false));
    add(ref.prepare({}, true));
    add(ref.prepare({}, false));
    for (const abb::ProgramEvent& e : program.events) {
        const auto head = e.nozzle == abb::Nozzle::pla ? drivers::Head::pla : drivers::Head::ccf;
        if (first_line) (*first_line)[e.sequence] = out.size();
        switch (e.kind) {
            case EventKind::head_switch: add(ref.select(head)); break;
            case EventKind::extrude_on:
                add(ref.prime());
                add(metered_pieces(e.length_mm, pla_ratio, e.speed_mm_s, 2));
                break;
            case EventKind::extrude_off: add(ref.retract()); break;
            case EventKind::fibre_start:
                add(ref.thread_fibre());
                out.push_back("M400");
                add(metered_pieces(e.length_mm, 1.0, e.speed_mm_s, 1));
                break;
            case EventKind::cut: add(ref.cut()); break;
            case EventKind::path_end:
            case EventKind::layer_end: break;
        }
    }
    return out;
}

class PrintCellTest : public SimCellFixture {
  protected:
    void TearDown() override {
        if (devices_) devices_->set_print(nullptr);
        session_.reset();
        SimCellFixture::TearDown();
    }

    // RAPID chunks of the program (small chunks so that FcMain loads several).
    static std::vector<abb::ChunkFile> chunks_of(const abb::PrintProgram& program) {
        std::vector<abb::ChunkFile> out;
        for (const auto& m : abb::write_rapid_chunks(program, abb::RobotCellConfig{}, {.max_lines = 36}).modules)
            out.push_back({m.file_name, m.text});
        return out;
    }

    PrintOptions options() const {
        PrintOptions o;
        o.heartbeat_timeout_s = 0.5;  // real s: the simulated controller scales it
        o.max_chunk_lines = 36;
        o.sync.time_scale = scale_;
        return o;
    }

    // The session prints a copy of `program` kept by the fixture, so that it outlives the
    // session even when a test ends early.
    void make_session(const abb::PrintProgram& program, std::vector<abb::ChunkFile> chunks,
                      PrintOptions o) {
        program_ = program;
        devices_->set_print(nullptr);
        session_ = std::make_unique<PrintSession>(program_, std::move(chunks), devices_->links(), o);
        devices_->set_print(session_.get());  // the links' events, as the service routes them
    }

    // Waits until the session meters the path of event `sequence` and has sent `pieces` of it.
    bool metering(std::int64_t sequence, std::size_t pieces) {
        return eventually([&] {
            const auto m = session_->poll().sync.metering;
            return m.active && m.sequence == sequence && m.pieces_sent >= pieces;
        });
    }

    // Where the robot's TCP (bed frame) was when the board executed something at its time t_s
    // (after the last sample the robot stands where it stopped).
    std::optional<Eigen::Vector3d> robot_at_board_time(
        const std::vector<drivers::sim::TrajectorySample>& trajectory, double board_t_s) const {
        const auto wall = mock().wall_at(board_t_s);
        if (!trajectory.empty() && wall > trajectory.back().wall) return trajectory.back().tcp_wobj_mm;
        const auto s = drivers::sim::sample_at(trajectory, wall);
        if (!s) return std::nullopt;
        return s->tcp_wobj_mm;
    }

    // How far off `point` (a path's start or end) the robot was when the board acted at its
    // simulated time `board_t_s`, in mm along the robot's path. Where the robot stood at the
    // point, the time it stood there before the action (`at_end`: since it arrived) or after it
    // (a start: until it left) counts at `speed_mm_s`: feed that goes on after the robot stopped
    // at a path's end, or starts before it leaves, is as far off as feed a distance away.
    std::optional<double> path_error_mm(const std::vector<drivers::sim::TrajectorySample>& trajectory,
                                        const Eigen::Vector3d& point, double board_t_s,
                                        bool at_end, double speed_mm_s) const {
        if (trajectory.empty()) return std::nullopt;
        const auto wall = mock().wall_at(board_t_s);
        const bool after_all = wall > trajectory.back().wall;
        const auto robot = after_all ? std::optional(trajectory.back())
                                     : drivers::sim::sample_at(trajectory, wall);
        if (!robot) return std::nullopt;
        // The stays at the point: runs of samples there; the one nearest the action in time.
        std::optional<std::pair<std::size_t, std::size_t>> stay;
        double nearest = 0;
        for (std::size_t i = 0; i < trajectory.size(); ++i) {
            if ((trajectory[i].tcp_wobj_mm - point).norm() > 1e-3) continue;
            std::size_t j = i;
            while (j + 1 < trajectory.size() && (trajectory[j + 1].tcp_wobj_mm - point).norm() <= 1e-3) ++j;
            const auto in = trajectory[i].wall, out = trajectory[j].wall;
            const double gap = wall < in ? seconds(in - wall) : wall > out ? seconds(wall - out) : 0;
            if (!stay || gap < nearest) stay = {i, j}, nearest = gap;
            i = j;
        }
        if (!stay) return std::nullopt;
        const auto& in = trajectory[stay->first];
        const auto& out = trajectory[stay->second];
        const bool stands_to_the_end = stay->second + 1 == trajectory.size();
        if (wall < in.wall) return in.path_mm - robot->path_mm;
        if (wall > out.wall && !stands_to_the_end) return robot->path_mm - out.path_mm;
        const double stood_s = at_end ? seconds(wall - in.wall) : seconds(out.wall - wall);
        return std::max(0.0, stood_s) * scale_ * speed_mm_s;
    }

    static double seconds(std::chrono::steady_clock::duration d) {
        return std::chrono::duration<double>(d).count();
    }

    abb::PrintProgram program_;
    std::unique_ptr<PrintSession> session_;
};

}  // namespace fibrecell::test
