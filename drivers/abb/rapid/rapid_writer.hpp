#pragma once
// The RAPID chunk writer: a print program as per-job chunk modules FcChunk0001.mod, ... that the
// resident main module FcMain loads one after another and calls by late binding
// (%"FcChunk0001"%). Each chunk is self-contained (LOCAL tool, work object, speed and zone data;
// triggdata in its one PROC), ends at a travel stop point and stays under the line limit. Every
// robtarget is inline, with confdata from the IRB 1200 inverse kinematics on the configured cfx
// branch, J4/J6 unwound continuously from target to target. Events are position-locked
// TriggIO/TriggEquip on the event group output; barriers call FcBarrier <sequence>.
// docs/robot-program.md describes the format; the output stays inside docs/rapid-subset.md.

#include "drivers/abb/cell/robot_config.hpp"
#include "drivers/abb/kinematics/joint_vector.hpp"
#include "drivers/abb/program/print_program.hpp"

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace fibrecell::drivers::abb {

// Names shared with the resident main module (FcMain).
inline constexpr std::string_view chunk_prefix = "FcChunk";  // + 4 digits, 1-based
inline constexpr std::string_view barrier_routine = "FcBarrier";
inline constexpr int max_chunks = 9999;

struct RapidWriterOptions {
    std::string job_name;        // for the header comment (non-ASCII and quotes are dropped)
    int max_lines = 0;           // per chunk; 0: the cell's rapid.max_chunk_lines
    JointVector start_joints{};  // joints before the first move [rad]: the first J4/J6 reference
    // A run that re-enters an interrupted print: > 0 starts the first chunk with a straight lift
    // this far up [mm] from wherever the robot stands, MoveL Offs(CRobT(..), 0, 0, lift), before
    // the program's first move. 0: none. Every chunk keeps room for these lines.
    double reentry_lift_mm = 0;
    // The first chunk's number (FcChunk<first_number>) and the job's chunk count for the header
    // comments (0: as many as written): a re-entry rewrites one chunk of a job in place.
    int first_number = 1;
    int chunk_count = 0;
};

struct RapidModule {
    std::string name;       // "FcChunk0001": module = routine = file stem
    std::string file_name;  // "FcChunk0001.mod"
    std::string text;       // ASCII, LF line ends
    std::size_t lines = 0;
    std::size_t first_move = 0, end_move = 0;  // PrintProgram::moves [first_move, end_move)
    int first_event = 0, last_event = 0;       // sequence numbers in the chunk; 0 when none
};

struct RapidStats {
    std::size_t modules = 0, lines = 0, bytes = 0;
    std::size_t moves = 0, triggers = 0, barriers = 0;
};

struct RapidOutput {
    std::vector<RapidModule> modules;
    std::vector<JointVector> joints;  // per program move: the solution its confdata comes from
    RapidStats stats;
};

// An unreachable target or a program that cannot be chunked; names the layer/path/point.
class RapidWriteError : public std::runtime_error {
  public:
    RapidWriteError(const std::string& what, std::size_t move, int layer, int path, int point)
        : std::runtime_error(what), move_(move), layer_(layer), path_(path), point_(point) {}
    std::size_t move() const { return move_; }
    int layer() const { return layer_; }
    int path() const { return path_; }
    int point() const { return point_; }

  private:
    std::size_t move_;
    int layer_, path_, point_;
};

RapidOutput write_rapid_chunks(const PrintProgram& program, const RobotCellConfig& cell,
                               const RapidWriterOptions& options = {});

}  // namespace fibrecell::drivers::abb
