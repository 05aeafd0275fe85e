#pragma once
// The print program: a plan's toolpaths as the robot will execute them, independent of RAPID
// syntax. An ordered list of moves (travel: lift, move at safe height, approach; print moves at
// the head's speed; head switches) with the active nozzle, the TCP pose in the bed frame, speed and
// zone, and the events the extruder board follows, each at an exact position and with a 1-based
// sequence number (what the robot puts on the event group output). docs/robot-program.md.
//
//   RobotCellConfig cell = load_robot_config(section);
//   PrintProgram p = build_print_program(layers, cell, {.pla_speed_mm_s = 12, ...});  // RobotLayer
//   RapidOutput r = write_rapid_chunks(p, cell, {});

#include "drivers/abb/cell/robot_config.hpp"
#include "drivers/abb/program/robot_path.hpp"

#include <Eigen/Geometry>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::drivers::abb {

enum class MoveRole {
    start,     // the program's first move: joint motion to above the first path
    lift,      // straight up from a path end to travel (or head-switch) height
    travel,    // to above the next path start
    turn,      // head switch: turn to the other nozzle's tilt, flange kept in place
    approach,  // straight down onto a path start; always a stop point
    print,     // along a toolpath at the head's print speed
};

enum class EventKind {
    extrude_on,   // PLA: prime and extrude; at the start of the path's first print move
    extrude_off,  // PLA: stop and retract; at the path end (also the PLA path's end)
    fibre_start,  // CCF: barrier at the path start while the feeder threads the fibre
    cut,          // CCF: feed stops and the cutter fires, cutter distance before the path end
    path_end,     // CCF: the fibre path's end (the last cutter distance was dragged out)
    layer_end,    // the layer is done: at the start of the lift after its last path
    head_switch,  // barrier: tool change and temperature (also before the first path)
};

std::string_view to_string(MoveRole r);
std::string_view to_string(EventKind k);

// Where on its move an event happens.
enum class EventAnchor {
    before,  // barrier: the robot waits before the move (the previous move ends in a stop point)
    start,   // at the move's start (TriggIO/TriggEquip \Start)
    end,     // at the move's end point (distance 0)
};

struct ProgramMove {
    MoveRole role = MoveRole::print;
    Nozzle nozzle = Nozzle::pla;  // the active nozzle: the tool of the move
    bool joint = false;           // joint interpolation (MoveJ) instead of linear
    Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();            // TCP at the end, bed frame
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // TCP in the bed frame
    double speed_mm_s = 0;
    double turn_speed_deg_s = 0;  // reorientation speed (speeddata v_ori)
    bool fine = false;            // stop point; otherwise fly-by with zone_mm
    double zone_mm = 0;
    double length_mm = 0;  // straight-line TCP travel of the move
    // The path the move belongs to (RobotLayer::index and the path's index in its layer)
    // and the point it ends at (index into RobotPath::points; the closing move of a closed path
    // ends at 0). -1 where none applies; point -1 on a print move = the inserted cut point.
    int layer = -1;
    int path = -1;
    int point = -1;
};

struct ProgramEvent {
    int sequence = 0;  // 1-based, running over the whole program
    EventKind kind = EventKind::layer_end;
    bool barrier = false;        // the robot waits until the service releases it
    bool equipment_lag = false;  // drives the extruder: TriggEquip with the configured lag
    std::size_t move = 0;        // index into PrintProgram::moves
    EventAnchor anchor = EventAnchor::end;
    Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();  // TCP in the bed frame
    Nozzle nozzle = Nozzle::pla;
    int layer = -1;
    int path = -1;
    // extrude_on: the PLA path's length; fibre_start: fibre fed up to the cut; cut: the rest of
    // the path (the cutter distance); 0 otherwise [mm].
    double length_mm = 0;
    double speed_mm_s = 0;  // print speed of the path (0 for layer_end, head_switch)
};

struct ProgramStats {
    std::size_t moves = 0, print_moves = 0, travel_moves = 0, fine_points = 0;
    std::size_t events = 0, barriers = 0;
    std::size_t layers = 0, paths = 0, head_switches = 0;
    std::size_t points_in = 0, points_merged = 0;  // toolpath points read / dropped by merging
    double print_length_mm = 0, travel_length_mm = 0;
    // Estimated time: move length / speed (turns: angle / turn speed), plus the fine-point
    // allowance per stop and the barrier allowances of ProgramOptions [s].
    double duration_s = 0;
};

struct PrintProgram {
    std::vector<ProgramMove> moves;
    std::vector<ProgramEvent> events;   // in sequence order (sequence = index + 1)
    std::vector<std::string> warnings;  // paths skipped (fewer than two distinct points)
    ProgramStats stats;
};

// The print's own settings (daemon/print/print_settings.hpp makes them from the job and the cell).
struct ProgramOptions {
    double pla_speed_mm_s = 12;          // job process.pla.speed_mm_s (paper Table 2)
    double ccf_speed_mm_s = 5;           // job process.ccf.speed_mm_s
    double pla_travel_speed_mm_s = 100;  // job process.pla.travel_speed_mm_s: lift, travel, turn
    double ccf_travel_speed_mm_s = 100;  // job process.ccf.travel_speed_mm_s
    double cutter_distance_mm = 42;      // the cell's extruder.ccf.cutter_distance_mm
    double fibre_thread_s = 0;       // duration estimate per fibre path start (thread feed)
    double head_switch_s = 0;        // duration estimate per head switch (tool change, heating)
};

// A planning error: where (RobotLayer::index, path, point; -1 where none) and what.
struct ProgramIssue {
    int layer = -1;
    int path = -1;
    int point = -1;
    std::string message;  // "layer 3 path 2 point 17: ..."
};

class PrintProgramError : public std::runtime_error {
  public:
    explicit PrintProgramError(std::vector<ProgramIssue> issues);
    const std::vector<ProgramIssue>& issues() const { return issues_; }

  private:
    std::vector<ProgramIssue> issues_;
};

// Layers in print order, points in the bed frame [mm]. The layer's nozzle decides the path kind:
// every path of a CCF layer is a fibre path (threading barrier, cut, path end). Throws PrintProgramError listing every problem: the idle nozzle tip closer than
// the clearance to the part's current top (highest z printed so far) at a print move or a head
// turn, a fibre path shorter than the cutter distance, a non-finite coordinate.
PrintProgram build_print_program(const std::vector<RobotLayer>& layers, const RobotCellConfig& cell,
                                 const ProgramOptions& options = {});

}  // namespace fibrecell::drivers::abb
