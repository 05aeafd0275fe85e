#include "daemon/print/print_plan.hpp"

#include "daemon/print/program_file.hpp"
#include "drivers/abb/rapid/rapid_writer.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

namespace fibrecell::daemon::print {
namespace {

namespace abb = drivers::abb;
namespace fs = std::filesystem;

std::string read_plan_file(const fs::path& dir, const std::string& name) {
    std::ifstream in(dir / name, std::ios::binary);
    std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in && !in.eof()) throw std::invalid_argument((dir / name).string() + ": cannot be read");
    return s;
}

bool listed(const Manifest& m, const std::string& name) {
    return std::any_of(m.files.begin(), m.files.end(),
                       [&](const ManifestEntry& e) { return e.path == name; });
}

// The chunk holding move `move` (0-based index into the chunk table).
std::size_t chunk_of(const PrintFile& print, std::size_t move) {
    for (std::size_t c = 0; c < print.chunks.size(); ++c)
        if (move >= print.chunks[c].first_move && move < print.chunks[c].end_move) return c;
    throw std::invalid_argument("print.json: no chunk holds move " + std::to_string(move + 1));
}

}  // namespace

abb::PrintProgram program_tail(const abb::PrintProgram& program, std::size_t first_move,
                               std::size_t end_move, std::int64_t first_event) {
    if (end_move == 0 || end_move > program.moves.size()) end_move = program.moves.size();
    abb::PrintProgram tail;
    tail.moves.assign(program.moves.begin() + static_cast<std::ptrdiff_t>(first_move),
                      program.moves.begin() + static_cast<std::ptrdiff_t>(end_move));
    for (const abb::ProgramEvent& e : program.events) {
        if (e.move < first_move || e.move >= end_move || e.sequence < first_event) continue;
        abb::ProgramEvent moved = e;
        moved.move -= first_move;
        tail.events.push_back(moved);
    }
    tail.stats = program.stats;
    return tail;
}

namespace {

// A re-entry's first move: a straight travel (up and over, not a joint move's curve) to a stop
// point, from wherever the robot was held.
void make_reentry_rise(abb::ProgramMove& m) {
    m.role = abb::MoveRole::travel;
    m.joint = false;
    m.fine = true;
    m.zone_mm = 0;
    m.length_mm = 0;
}

// Where `along_mm` of a fibre path's feed ends: the print move it falls on (from its fibre_start's
// move on) and the point on it.
struct PathPoint {
    std::size_t move = 0;
    Eigen::Vector3d at = Eigen::Vector3d::Zero();
    double left_mm = 0;  // of that move, from the point to its end
};

PathPoint point_along(const abb::PrintProgram& program, const abb::ProgramEvent& start,
                      double along_mm) {
    double before = 0;
    for (std::size_t m = start.move; m < program.moves.size(); ++m) {
        const abb::ProgramMove& move = program.moves[m];
        if (move.role != abb::MoveRole::print || move.path != start.path || move.layer != start.layer)
            break;
        if (before + move.length_mm > along_mm) {
            const Eigen::Vector3d from = program.moves[m - 1].position_mm;
            const double t = move.length_mm > 0 ? (along_mm - before) / move.length_mm : 0.0;
            return {m, from + t * (move.position_mm - from), before + move.length_mm - along_mm};
        }
        before += move.length_mm;
    }
    throw std::invalid_argument("re-entry: fibre path of event " + std::to_string(start.sequence) +
                                " is shorter than the " + std::to_string(along_mm) + " mm fed");
}

// A fibre path re-entered `resume.fibre_fed_mm` along it: the rise to above that point, the
// approach onto it, the rest of its move and the path's later moves, the fibre_start (a new
// thread) before them.
abb::PrintProgram reentry_mid_path(const abb::PrintProgram& program, const ResumePoint& resume,
                                   std::size_t end_move) {
    const abb::ProgramEvent& start = program.events[static_cast<std::size_t>(resume.first_event - 1)];
    const PathPoint q = point_along(program, start, resume.fibre_fed_mm);
    abb::PrintProgram run = program_tail(program, q.move, end_move, resume.first_event + 1);
    const abb::ProgramMove& planned_travel = program.moves[resume.first_move - 1];
    const abb::ProgramMove& planned_approach = program.moves[resume.first_move];
    abb::ProgramMove rise = planned_travel;
    make_reentry_rise(rise);
    rise.position_mm = {q.at.x(), q.at.y(), planned_travel.position_mm.z()};
    rise.orientation = planned_approach.orientation;
    abb::ProgramMove approach = planned_approach;
    approach.position_mm = q.at;
    approach.length_mm = rise.position_mm.z() - q.at.z();
    approach.point = -1;
    run.moves.front().length_mm = q.left_mm;
    run.moves.insert(run.moves.begin(), {rise, approach});
    for (abb::ProgramEvent& e : run.events) e.move += 2;
    abb::ProgramEvent thread = start;
    thread.move = 2;
    thread.position_mm = q.at;
    run.events.insert(run.events.begin(), thread);
    return run;
}

}  // namespace

std::size_t reentry_move(const abb::PrintProgram& program, const ResumePoint& resume) {
    if (resume.fibre_fed_mm > 0)
        return point_along(program, program.events[static_cast<std::size_t>(resume.first_event - 1)],
                           resume.fibre_fed_mm)
            .move;
    return resume.first_move - 1;
}

abb::PrintProgram reentry_program(const abb::PrintProgram& program, const ResumePoint& resume,
                                  std::size_t end_move) {
    // build_print_program ends every travel above the next path start, then approaches.
    if (resume.first_move == 0 || resume.first_move >= program.moves.size())
        throw std::invalid_argument("re-entry: move " + std::to_string(resume.first_move) +
                                    " is no approach after a travel");
    if (resume.fibre_fed_mm > 0) return reentry_mid_path(program, resume, end_move);
    abb::PrintProgram run =
        program_tail(program, resume.first_move - 1, end_move, resume.first_event);
    make_reentry_rise(run.moves.front());
    return run;
}

PrintPlan load_print_plan(const fs::path& plan_dir, const CellConfig& cell,
                          std::optional<std::int64_t> last_confirmed,
                          std::optional<FibreFed> fed) {
    const Manifest manifest = check_plan(plan_dir, cell);
    if (!listed(manifest, "print.json") || !listed(manifest, "program.json"))
        throw PlanRefused("the plan has no print (print.json, program.json): it was planned with "
                          "--stage field; plan the job whole");
    PrintPlan p;
    p.print = parse_print_json(read_plan_file(plan_dir, "print.json"),
                               (plan_dir / "print.json").string());
    ProgramFile program = parse_program_json(read_plan_file(plan_dir, "program.json"),
                                             (plan_dir / "program.json").string());
    p.program = std::move(program.program);
    p.joints = std::move(program.joints);
    p.chunk_count = static_cast<int>(p.print.chunks.size());

    std::size_t first_stored = 0;  // the first planned chunk this run uploads as it is
    if (last_confirmed) {
        p.resume = resume_point(p.program, *last_confirmed, fed);
        if (p.resume->nothing_left) {
            p.first_event = static_cast<std::int64_t>(p.program.events.size()) + 1;
            p.first_chunk = p.chunk_count + 1;
            return p;
        }
        p.first_event = p.resume->first_event;
        p.skip_events = p.resume->done_in_unit;
        // The interrupted chunk, from the travel into the unit (or the move re-entered in the
        // middle of a fibre path) on, with the lift first.
        const std::size_t rise = reentry_move(p.program, *p.resume);
        const std::size_t c = chunk_of(p.print, rise);
        const ChunkEntry& entry = p.print.chunks[c];
        const abb::RapidOutput rapid = abb::write_rapid_chunks(
            reentry_program(p.program, *p.resume, entry.end_move), cell.robot,
            {.job_name = p.print.job,
             .start_joints = rise > 0 ? p.joints[rise - 1] : abb::JointVector{},
             .reentry_lift_mm = cell.robot.motion.safe_height_mm,
             .first_number = static_cast<int>(c) + 1,
             .chunk_count = p.chunk_count});
        if (rapid.modules.size() != 1)
            throw std::invalid_argument("re-entry: the rest of " + entry.file + " needs " +
                                        std::to_string(rapid.modules.size()) + " chunks, not one");
        p.chunks.push_back({rapid.modules.front().file_name, rapid.modules.front().text});
        p.first_chunk = static_cast<int>(c) + 1;
        first_stored = c + 1;
    }
    for (std::size_t c = first_stored; c < p.print.chunks.size(); ++c) {
        const std::string& file = p.print.chunks[c].file;
        p.chunks.push_back({fs::path(file).filename().string(), read_plan_file(plan_dir, file)});
    }
    return p;
}

}  // namespace fibrecell::daemon::print
