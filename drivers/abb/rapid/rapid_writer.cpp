#include "drivers/abb/rapid/rapid_writer.hpp"

#include "drivers/abb/kinematics/joint_solver.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>

namespace fibrecell::drivers::abb {
namespace {

// TriggL takes its trigger plus \T2..\T8.
constexpr std::size_t max_triggers_per_move = 8;

// Fixed-point text with `decimals` digits; no "-0.000".
void append_fixed(std::string& out, double v, int decimals) {
    char buf[64];
    auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
    const std::string_view s(buf, static_cast<std::size_t>(r.ptr - buf));
    if (s.front() == '-' && s.find_first_not_of("-0.") == std::string_view::npos) {
        out.append(s.substr(1));
        return;
    }
    out.append(s);
}

// Shortest text that reads back as `v` (speeds, zones, masses: "12", "0.3").
void append_number(std::string& out, double v) {
    char buf[64];
    auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
}

void append_int(std::string& out, long v) {
    char buf[32];
    auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
}

// Unit quaternion [w, x, y, z] with w >= 0 (q and -q are the same rotation).
Eigen::Quaterniond canonical(const Eigen::Quaterniond& q) {
    Eigen::Quaterniond n = q.normalized();
    if (n.w() < 0) n.coeffs() *= -1;
    return n;
}

void append_quaternion(std::string& out, const Eigen::Quaterniond& q_in) {
    const Eigen::Quaterniond q = canonical(q_in);
    out += '[';
    append_fixed(out, q.w(), 6);
    out += ',';
    append_fixed(out, q.x(), 6);
    out += ',';
    append_fixed(out, q.y(), 6);
    out += ',';
    append_fixed(out, q.z(), 6);
    out += ']';
}

void append_pos(std::string& out, const Eigen::Vector3d& p, int decimals) {
    out += '[';
    append_fixed(out, p.x(), decimals);
    out += ',';
    append_fixed(out, p.y(), decimals);
    out += ',';
    append_fixed(out, p.z(), decimals);
    out += ']';
}

void append_pose(std::string& out, const Eigen::Isometry3d& t) {
    out += '[';
    append_pos(out, t.translation(), 6);
    out += ',';
    append_quaternion(out, Eigen::Quaterniond(t.linear()));
    out += ']';
}

std::string tool_name(Nozzle n) {
    return n == Nozzle::pla ? "tFcPla" : "tFcCcf";
}

std::string describe(const ProgramMove& m, std::size_t index) {
    std::string s;
    // Counted from 1, as people count them (and the dashboard, the CLI and result.json).
    if (m.layer >= 0) s += "layer " + std::to_string(m.layer + 1);
    if (m.path >= 0) s += " path " + std::to_string(m.path + 1);
    if (m.point >= 0) s += " point " + std::to_string(m.point + 1);
    if (m.role == MoveRole::print && m.point < 0) s += " cut point";
    if (!s.empty()) s += ", ";
    s += std::string(to_string(m.role)) + " move " + std::to_string(index + 1);
    if (s.front() == ' ') s.erase(0, 1);
    return s;
}

std::string sanitize_comment(const std::string& text, std::size_t max) {
    std::string s;
    for (const char c : text)
        if (c >= 0x20 && c < 0x7f && c != '"') s += c;
    if (s.size() > max) s.resize(max);
    return s;
}

// Speed and zone data the chunks declare: one entry per distinct value, named after the role of
// the first move that uses it.
struct DataNames {
    std::map<double, std::string> speeds;  // v_tcp -> name
    std::map<double, std::string> zones;   // zone radius -> name
    double turn_speed_deg_s = 0;
};

std::string unique_name(const std::string& base, const std::map<double, std::string>& taken) {
    std::string name = base;
    for (int k = 2;; ++k) {
        const bool used = std::any_of(taken.begin(), taken.end(),
                                      [&](const auto& kv) { return kv.second == name; });
        if (!used) return name;
        name = base + "_" + std::to_string(k);
    }
}

DataNames data_names(const PrintProgram& program, const RobotCellConfig& cell) {
    DataNames d;
    d.turn_speed_deg_s = cell.motion.turn_speed_deg_s;
    for (const ProgramMove& m : program.moves) {
        if (!d.speeds.contains(m.speed_mm_s)) {
            std::string base = m.role == MoveRole::print
                                   ? (m.nozzle == Nozzle::pla ? "vFcPla" : "vFcCcf")
                               : m.role == MoveRole::approach ? "vFcApproach"
                                                              : "vFcTravel";
            d.speeds[m.speed_mm_s] = unique_name(base, d.speeds);
        }
        if (!m.fine && !d.zones.contains(m.zone_mm)) {
            const std::string base = m.role == MoveRole::print ? "zFcPrint" : "zFcTravel";
            d.zones[m.zone_mm] = unique_name(base, d.zones);
        }
    }
    return d;
}

struct MoveLines {
    std::size_t barriers = 0, triggers = 0, comment = 0;
    std::size_t total() const { return 1 + barriers + triggers + comment; }
};

class ChunkWriter {
  public:
    ChunkWriter(const PrintProgram& program, const RobotCellConfig& cell,
                const RapidWriterOptions& options, const std::vector<JointVector>& joints)
        : program_(program),
          cell_(cell),
          options_(options),
          joints_(joints),
          geometry_(cell.model().geometry),
          names_(data_names(program, cell)) {
        // Events are sorted by move: those of move m are [events_of_move_[m], [m + 1]).
        events_of_move_.assign(program.moves.size() + 1, 0);
        std::size_t e = 0;
        for (std::size_t m = 0; m <= program.moves.size(); ++m) {
            events_of_move_[m] = e;
            while (e < program.events.size() && program.events[e].move == m) ++e;
        }
        for (std::size_t m = 0; m < program.moves.size(); ++m) {
            std::size_t t = 0;
            for (std::size_t i = events_of_move_[m]; i < events_of_move_[m + 1]; ++i)
                if (!program.events[i].barrier) ++t;
            if (t > max_triggers_per_move)
                throw RapidWriteError(describe(program.moves[m], m) + ": " + std::to_string(t) +
                                          " events on one move, TriggL takes at most 8",
                                      m, program.moves[m].layer, program.moves[m].path,
                                      program.moves[m].point);
            trigger_vars_ = std::max(trigger_vars_, t);
        }
    }

    // Lines outside the moves: module, header comment, tools, work object, speeds, zones, blank,
    // PROC, triggdata, ConfJ, ConfL, ENDPROC, ENDMODULE.
    std::size_t overhead_lines() const {
        return 5 + names_.speeds.size() + names_.zones.size() + 2 + trigger_vars_ + 2 + 2;
    }

    // Lines a re-entry lift takes (a comment and the MoveL). Every chunk keeps room for them, so
    // that the re-entry version of any chunk fits the limit as well (daemon/print/print_plan).
    static constexpr std::size_t lift_lines = 2;

    MoveLines lines_of(std::size_t m) const {
        MoveLines l;
        for (std::size_t i = events_of_move_[m]; i < events_of_move_[m + 1]; ++i)
            (program_.events[i].barrier ? l.barriers : l.triggers) += 1;
        l.comment = program_.moves[m].role == MoveRole::approach ? 1 : 0;
        return l;
    }

    // `lift`: the chunk starts with the re-entry lift.
    RapidModule write(int number, int count, std::size_t first, std::size_t end, bool lift) const {
        RapidModule mod;
        char digits[16];  // room for any int: GCC checks the format against the type
        std::snprintf(digits, sizeof digits, "%04d", number);
        mod.name = std::string(chunk_prefix) + digits;
        mod.file_name = mod.name + ".mod";
        mod.first_move = first;
        mod.end_move = end;
        std::string& t = mod.text;
        t.reserve((end - first) * 140 + 2048);

        t += "MODULE " + mod.name + "\n";
        t += "  ! fibrecell print chunk " + std::to_string(number) + " of " + std::to_string(count);
        if (!options_.job_name.empty()) t += ", job " + sanitize_comment(options_.job_name, 40);
        t += ", moves " + std::to_string(first + 1) + "-" + std::to_string(end);
        if (events_of_move_[first] < events_of_move_[end]) {
            mod.first_event = program_.events[events_of_move_[first]].sequence;
            mod.last_event = program_.events[events_of_move_[end] - 1].sequence;
            t += ", events " + std::to_string(mod.first_event) + "-" +
                 std::to_string(mod.last_event);
        }
        t += "\n";
        for (const Nozzle n : {Nozzle::pla, Nozzle::ccf}) {
            const NozzleConfig& z = cell_.head.nozzle(n);
            t += "  LOCAL PERS tooldata " + tool_name(n) + " := [TRUE,";
            append_pose(t, z.tframe);
            t += ",[";
            append_number(t, z.mass_kg);
            t += ',';
            append_pos(t, z.cog_mm, 3);
            t += ",[1,0,0,0],0,0,0]];\n";
        }
        t += "  LOCAL PERS wobjdata wFcBed := [FALSE,TRUE,\"\",";
        append_pose(t, cell_.bed);
        t += ",[[0,0,0],[1,0,0,0]]];\n";
        for (const auto& [v, name] : names_.speeds) {
            t += "  LOCAL CONST speeddata " + name + " := [";
            append_number(t, v);
            t += ',';
            append_number(t, names_.turn_speed_deg_s);
            t += ",5000,1000];\n";
        }
        for (const auto& [z, name] : names_.zones) {
            // The predefined zones' proportions (docs/rapid-subset.md, "Predefined data"): tcp,
            // 1.5x ori and eax, 0.15x deg.
            t += "  LOCAL CONST zonedata " + name + " := [FALSE,";
            for (const double k : {1.0, 1.5, 1.5, 0.15, 1.5, 0.15}) {
                append_number(t, std::round(z * k * 1e4) / 1e4);
                t += ',';
            }
            t.back() = ']';
            t += ";\n";
        }
        t += "\n  PROC " + mod.name + "()\n";
        for (std::size_t i = 1; i <= trigger_vars_; ++i)
            t += "    VAR triggdata tgFc" + std::to_string(i) + ";\n";
        t += "    ConfJ \\On;\n";
        t += cell_.rapid.confl ? "    ConfL \\On;\n" : "    ConfL \\Off;\n";
        if (lift) write_lift(t, program_.moves[first]);
        for (std::size_t m = first; m < end; ++m) write_move(t, m);
        t += "  ENDPROC\n";
        t += "ENDMODULE\n";
        mod.lines = static_cast<std::size_t>(std::count(t.begin(), t.end(), '\n'));
        return mod;
    }

  private:
    // Straight up from wherever the robot was held, keeping its orientation, with the tool and
    // speed of the program's first move: CRobT with any tool gives the flange's pose, and a pure
    // translation of one TCP is one of the flange.
    void write_lift(std::string& t, const ProgramMove& first) const {
        const std::string tool = tool_name(first.nozzle);
        t += "    ! re-entry: straight up from where the robot was held\n";
        t += "    MoveL Offs(CRobT(\\Tool:=" + tool + " \\WObj:=wFcBed),0,0,";
        append_number(t, options_.reentry_lift_mm);
        t += "), " + names_.speeds.at(first.speed_mm_s) + ", fine, " + tool + " \\WObj:=wFcBed;\n";
    }

    void write_move(std::string& t, std::size_t mi) const {
        const ProgramMove& m = program_.moves[mi];
        const std::string& signal = cell_.signals.event;
        if (m.role == MoveRole::approach) {
            t += "    ! layer " + std::to_string(m.layer) + " path " + std::to_string(m.path) +
                 " " + std::string(to_string(m.nozzle)) + "\n";
        }
        std::vector<std::string> triggers;
        for (std::size_t i = events_of_move_[mi]; i < events_of_move_[mi + 1]; ++i) {
            const ProgramEvent& e = program_.events[i];
            const long value = e.sequence % 65536;
            if (e.barrier) {
                t += "    " + std::string(barrier_routine) + " ";
                append_int(t, value);
                t += ";\n";
                continue;
            }
            const std::string var = "tgFc" + std::to_string(triggers.size() + 1);
            triggers.push_back(var);
            const char* start = e.anchor == EventAnchor::start ? " \\Start" : "";
            if (e.equipment_lag) {
                t += "    TriggEquip " + var + ", 0" + start + ", ";
                append_number(t, cell_.rapid.trigger_lag_s);
            } else {
                t += "    TriggIO " + var + ", 0" + start;
            }
            t += " \\GOp:=" + signal + ", ";
            append_int(t, value);
            t += ";\n";
        }
        const bool trigg = !triggers.empty();
        t += m.joint ? (trigg ? "    TriggJ " : "    MoveJ ")
                     : (trigg ? "    TriggL " : "    MoveL ");
        t += '[';
        append_pos(t, m.position_mm, 3);
        t += ',';
        append_quaternion(t, m.orientation);
        t += ',';
        t += to_string(confdata(geometry_, joints_[mi]));
        t += ",[9E9,9E9,9E9,9E9,9E9,9E9]], ";
        t += names_.speeds.at(m.speed_mm_s);
        if (trigg) {
            t += ", " + triggers[0];
            for (std::size_t k = 1; k < triggers.size(); ++k)
                t += " \\T" + std::to_string(k + 1) + ":=" + triggers[k];
        }
        t += ", ";
        t += m.fine ? std::string("fine") : names_.zones.at(m.zone_mm);
        t += ", " + tool_name(m.nozzle) + " \\WObj:=wFcBed;\n";
    }

    const PrintProgram& program_;
    const RobotCellConfig& cell_;
    const RapidWriterOptions& options_;
    const std::vector<JointVector>& joints_;
    OpwParameters geometry_;
    DataNames names_;
    std::vector<std::size_t> events_of_move_;
    std::size_t trigger_vars_ = 0;
};

std::vector<JointVector> solve_moves(const PrintProgram& program, const RobotCellConfig& cell,
                                     const RapidWriterOptions& options) {
    const RobotModel robot = cell.model();
    const TcpFrames frames[2] = {cell.frames(Nozzle::pla), cell.frames(Nozzle::ccf)};
    std::vector<JointVector> joints;
    joints.reserve(program.moves.size());
    JointVector reference = options.start_joints;
    for (std::size_t i = 0; i < program.moves.size(); ++i) {
        const ProgramMove& m = program.moves[i];
        Eigen::Isometry3d target = Eigen::Isometry3d::Identity();
        target.linear() = m.orientation.normalized().toRotationMatrix();
        target.translation() = m.position_mm;
        const IkResult r = solve_tcp(robot, frames[m.nozzle == Nozzle::pla ? 0 : 1], target,
                                     reference, cell.solver);
        if (!r.ok())
            throw RapidWriteError(describe(m, i) + ": target unreachable on cfx " +
                                      std::to_string(cell.solver.cfx) + ": " + r.failure.reason,
                                  i, m.layer, m.path, m.point);
        joints.push_back(r.joints);
        reference = r.joints;
    }
    return joints;
}

// Chunk boundaries: each chunk ends after a travel stop point and fits the line limit.
std::vector<std::pair<std::size_t, std::size_t>> split_chunks(const PrintProgram& program,
                                                              const ChunkWriter& writer,
                                                              std::size_t max_lines) {
    std::vector<std::pair<std::size_t, std::size_t>> chunks;
    const std::size_t n = program.moves.size();
    const std::size_t overhead = writer.overhead_lines();
    if (overhead + ChunkWriter::lift_lines >= max_lines)
        throw RapidWriteError("a chunk of at most " + std::to_string(max_lines) +
                                  " lines cannot hold its " + std::to_string(overhead) +
                                  " lines of declarations",
                              0, -1, -1, -1);
    const auto boundary = [&](std::size_t m) {
        const ProgramMove& mv = program.moves[m];
        return mv.fine && mv.role != MoveRole::print;
    };
    std::size_t first = 0;
    while (first < n) {
        std::size_t lines = overhead + ChunkWriter::lift_lines, last_boundary = 0;
        bool have_boundary = false;
        std::size_t m = first;
        for (; m < n; ++m) {
            const std::size_t add = writer.lines_of(m).total();
            if (lines + add > max_lines) break;
            lines += add;
            if (boundary(m)) {
                last_boundary = m;
                have_boundary = true;
            }
        }
        if (m == n && (have_boundary && last_boundary == n - 1)) {
            chunks.emplace_back(first, n);
            break;
        }
        if (!have_boundary) {
            const ProgramMove& mv = program.moves[first];
            throw RapidWriteError(describe(mv, first) +
                                      ": the moves up to the next travel stop "
                                      "point need more than the " +
                                      std::to_string(max_lines) + "-line chunk limit",
                                  first, mv.layer, mv.path, mv.point);
        }
        chunks.emplace_back(first, last_boundary + 1);
        first = last_boundary + 1;
    }
    return chunks;
}

}  // namespace

RapidOutput write_rapid_chunks(const PrintProgram& program, const RobotCellConfig& cell,
                               const RapidWriterOptions& options) {
    RapidOutput out;
    if (!(options.reentry_lift_mm >= 0 && options.reentry_lift_mm < 1000))
        throw RapidWriteError("re-entry lift " + std::to_string(options.reentry_lift_mm) +
                                  " mm is not 0..1000",
                              0, -1, -1, -1);
    if (program.moves.empty()) return out;
    out.joints = solve_moves(program, cell, options);
    const ChunkWriter writer(program, cell, options, out.joints);
    const std::size_t max_lines = static_cast<std::size_t>(
        options.max_lines > 0 ? options.max_lines : cell.rapid.max_chunk_lines);
    const auto chunks = split_chunks(program, writer, max_lines);
    const int first = options.first_number;
    if (first < 1 || chunks.size() > static_cast<std::size_t>(max_chunks - first + 1))
        throw RapidWriteError("the program needs " + std::to_string(chunks.size()) +
                                  " chunks from FcChunk" + std::to_string(first) +
                                  " on, more than the " + std::to_string(max_chunks) +
                                  " that four-digit chunk names allow",
                              0, -1, -1, -1);
    const int count = static_cast<int>(chunks.size());
    const int total = options.chunk_count > 0 ? options.chunk_count : first - 1 + count;
    for (int c = 0; c < count; ++c) {
        out.modules.push_back(writer.write(first + c, total, chunks[c].first, chunks[c].second,
                                           c == 0 && options.reentry_lift_mm > 0));
        const RapidModule& mod = out.modules.back();
        out.stats.lines += mod.lines;
        out.stats.bytes += mod.text.size();
        for (std::size_t m = mod.first_move; m < mod.end_move; ++m) {
            const MoveLines l = writer.lines_of(m);
            out.stats.triggers += l.triggers;
            out.stats.barriers += l.barriers;
        }
    }
    out.stats.modules = out.modules.size();
    out.stats.moves = program.moves.size();
    return out;
}

}  // namespace fibrecell::drivers::abb
