#include "drivers/abb/program/print_program.hpp"

#include "drivers/abb/program/point_merge.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace fibrecell::drivers::abb {
namespace {

constexpr std::size_t no_index = std::numeric_limits<std::size_t>::max();
constexpr int turn_samples = 16;  // clearance checks along a head turn

// A toolpath ready for the robot: closed paths end at their first point again; the cut point of
// a fibre path is inserted as a point of its own.
struct PreparedPath {
    std::vector<Eigen::Vector2d> points;
    std::vector<int> source;  // index into RobotPath::points; -1 for the inserted cut point
    double length_mm = 0;
    std::size_t cut = no_index;  // index into points
};

// Counted from 1, as people count them (the plan's files count from 0).
std::string where(int layer, int path, int point) {
    std::ostringstream s;
    s << "layer " << layer + 1;
    if (path >= 0) s << " path " << path + 1;
    if (point >= 0) s << " point " << point + 1;
    return s.str();
}

std::string mm(double v) {
    std::ostringstream s;
    s.precision(3);
    s << std::fixed << v << " mm";
    return s.str();
}

std::vector<double> arc_lengths(const std::vector<Eigen::Vector2d>& p) {
    std::vector<double> s(p.size(), 0.0);
    for (std::size_t i = 1; i < p.size(); ++i) s[i] = s[i - 1] + (p[i] - p[i - 1]).norm();
    return s;
}

class Builder {
  public:
    Builder(const RobotCellConfig& cell, const ProgramOptions& options)
        : cell_(cell), options_(options) {
        for (const Nozzle n : {Nozzle::pla, Nozzle::ccf})
            orientation_[index(n)] = print_orientation(cell.head, n);
    }

    void add_layer(const RobotLayer& layer) {
        if (!std::isfinite(layer.z)) {
            issue(layer.index, -1, -1, "the layer height is not a finite number");
            return;
        }
        int last = -1;
        std::vector<PreparedPath> prepared(layer.paths.size());
        for (std::size_t p = 0; p < layer.paths.size(); ++p)
            if (prepare(layer, static_cast<int>(p), prepared[p])) last = static_cast<int>(p);
        if (last < 0) {
            program_.warnings.push_back(where(layer.index, -1, -1) + ": no printable path");
            return;
        }
        ++program_.stats.layers;
        for (int p = 0; p <= last; ++p)
            if (!prepared[p].points.empty()) print_path(layer, p, prepared[p], p == last);
    }

    PrintProgram finish() {
        if (started_) {
            // Off the part at the end (the resident main module then goes to its safe position).
            const double z = std::max(part_top_, position_.z()) + cell_.motion.safe_height_mm;
            emit(travel_move(MoveRole::lift, {position_.x(), position_.y(), z}, true));
        }
        if (!issues_.empty()) throw PrintProgramError(std::move(issues_));
        number_events();
        compute_stats();
        return std::move(program_);
    }

  private:
    static std::size_t index(Nozzle n) { return n == Nozzle::pla ? 0 : 1; }

    void issue(int layer, int path, int point, const std::string& what) {
        issues_.push_back({layer, path, point, where(layer, path, point) + ": " + what});
    }

    // Points, closing point, cut point; false (with a warning or an issue) when there is
    // nothing to print.
    bool prepare(const RobotLayer& layer, int p, PreparedPath& out) {
        const RobotPath& path = layer.paths[p];
        program_.stats.points_in += path.points.size();
        for (std::size_t i = 0; i < path.points.size(); ++i)
            if (!path.points[i].allFinite()) {
                issue(layer.index, p, static_cast<int>(i), "coordinate is not a finite number");
                return false;
            }
        out.points = path.points;
        out.source.resize(path.points.size());
        for (std::size_t i = 0; i < out.source.size(); ++i) out.source[i] = static_cast<int>(i);
        if (path.closed && path.points.size() > 1) {
            out.points.push_back(path.points.front());
            out.source.push_back(0);
        }
        const std::vector<double> s = arc_lengths(out.points);
        out.length_mm = s.empty() ? 0 : s.back();
        if (out.points.size() < 2 || out.length_mm < 1e-6) {
            program_.warnings.push_back(where(layer.index, p, -1) +
                                        ": skipped, fewer than two distinct points");
            out = {};
            return false;
        }
        if (layer.nozzle == Nozzle::ccf) {
            const double d = options_.cutter_distance_mm;
            const double s_cut = out.length_mm - d;
            if (s_cut < -1e-9) {
                issue(layer.index, p, -1,
                      "fibre path of " + mm(out.length_mm) +
                          " is shorter than the cutter distance " + mm(d));
                out = {};
                return false;
            }
            insert_cut(out, s, std::max(s_cut, 0.0));
        }
        return true;
    }

    static void insert_cut(PreparedPath& out, const std::vector<double>& s, double s_cut) {
        constexpr double snap_mm = 1e-9;
        if (s_cut <= snap_mm) {
            out.cut = 0;
            return;
        }
        std::size_t i = 0;
        while (i + 2 < s.size() && s[i + 1] < s_cut) ++i;  // s[i] < s_cut <= s[i + 1]
        if (s[i + 1] - s_cut <= snap_mm) {
            out.cut = i + 1;
            return;
        }
        const double t = (s_cut - s[i]) / (s[i + 1] - s[i]);
        const Eigen::Vector2d c = out.points[i] + t * (out.points[i + 1] - out.points[i]);
        out.points.insert(out.points.begin() + static_cast<std::ptrdiff_t>(i + 1), c);
        out.source.insert(out.source.begin() + static_cast<std::ptrdiff_t>(i + 1), -1);
        out.cut = i + 1;
    }

    ProgramMove travel_move(MoveRole role, const Eigen::Vector3d& to, bool fine) const {
        ProgramMove m;
        m.role = role;
        m.nozzle = nozzle_;
        m.position_mm = to;
        m.orientation = orientation_[index(nozzle_)];
        m.speed_mm_s =
            role == MoveRole::approach ? cell_.motion.approach_speed_mm_s
            : nozzle_ == Nozzle::pla   ? options_.pla_travel_speed_mm_s
                                       : options_.ccf_travel_speed_mm_s;
        m.turn_speed_deg_s = cell_.motion.turn_speed_deg_s;
        m.fine = fine;
        m.zone_mm = fine ? 0 : cell_.motion.travel_zone_mm;
        m.layer = layer_;  // the path just printed (lifts); travel_to sets the next one
        m.path = path_;
        return m;
    }

    // Appends a move starting where the previous one ended; a pending layer end goes on its start.
    std::size_t emit(ProgramMove m) {
        m.length_mm = started_ ? (m.position_mm - position_).norm() : 0;
        const std::size_t i = program_.moves.size();
        program_.moves.push_back(m);
        if (pending_layer_end_) {
            event(EventKind::layer_end, i, EventAnchor::start, position_, pending_layer_, -1);
            pending_layer_end_ = false;
        }
        if (pending_barrier_) {
            ProgramEvent& e =
                event(EventKind::head_switch, i, EventAnchor::before, position_, m.layer, m.path);
            e.barrier = true;
            pending_barrier_ = false;
        }
        position_ = m.position_mm;
        rotation_ = m.orientation;
        nozzle_ = m.nozzle;
        started_ = true;
        return i;
    }

    ProgramEvent& event(EventKind kind, std::size_t move, EventAnchor anchor,
                        const Eigen::Vector3d& at, int layer, int path) {
        ProgramEvent e;
        e.kind = kind;
        e.move = move;
        e.anchor = anchor;
        e.position_mm = at;
        e.nozzle = program_.moves[move].nozzle;
        e.layer = layer;
        e.path = path;
        program_.events.push_back(e);
        return program_.events.back();
    }

    // Lift, head switch (lift to head-switch height, turn, barrier), travel, approach.
    void travel_to(const Eigen::Vector3d& start, Nozzle n, int layer, int path) {
        const double z_travel = std::max(part_top_, start.z()) + cell_.motion.safe_height_mm;
        const Eigen::Vector3d above(start.x(), start.y(), z_travel);
        if (!started_) {
            nozzle_ = n;
            ProgramMove m = travel_move(MoveRole::start, above, true);
            m.joint = true;
            m.layer = layer;
            m.path = path;
            emit(m);
            pending_barrier_ = true;  // select the first nozzle, wait for its temperature
        } else if (n != nozzle_) {
            const double z_switch =
                std::max(part_top_, start.z()) +
                std::max(cell_.motion.head_switch_height_mm, cell_.motion.safe_height_mm);
            emit(travel_move(MoveRole::lift,
                             {position_.x(), position_.y(), std::max(z_switch, position_.z())},
                             true));
            turn_to(n, layer, path);
            pending_barrier_ = true;
            ProgramMove m = travel_move(MoveRole::travel, above, false);
            m.layer = layer;
            m.path = path;
            emit(m);
        } else {
            if (position_.z() < z_travel - 1e-9)
                emit(travel_move(MoveRole::lift, {position_.x(), position_.y(), z_travel}, false));
            if ((above - position_).norm() > 1e-6) {  // not already above the start
                ProgramMove m = travel_move(MoveRole::travel, above, false);
                m.layer = layer;
                m.path = path;
                emit(m);
            }
        }
        ProgramMove m = travel_move(MoveRole::approach, start, true);
        m.layer = layer;
        m.path = path;
        m.point = 0;
        emit(m);
    }

    // The head turns to nozzle `n`'s tilt about the flange, which stays where it is; both tips
    // are checked against the part along the way.
    void turn_to(Nozzle n, int layer, int path) {
        const auto& head = cell_.head;
        Eigen::Isometry3d tcp_old = Eigen::Isometry3d::Identity();
        tcp_old.linear() = rotation_.toRotationMatrix();
        tcp_old.translation() = position_;
        const Eigen::Isometry3d flange =
            tcp_old * head.nozzle(nozzle_).tframe.inverse(Eigen::Isometry);
        const Eigen::Isometry3d from = flange * head.nozzle(n).tframe;  // new TCP before the turn
        const Eigen::Quaterniond q_from(from.linear());
        const Eigen::Quaterniond q_to = orientation_[index(n)];
        Eigen::Isometry3d flange_to = Eigen::Isometry3d::Identity();
        flange_to.linear() = q_to.toRotationMatrix() * head.nozzle(n).tframe.linear().transpose();
        flange_to.translation() = flange.translation();
        const Eigen::Vector3d to = flange_to * head.nozzle(n).tframe.translation();

        for (int k = 0; k <= turn_samples; ++k) {
            const double t = static_cast<double>(k) / turn_samples;
            Eigen::Isometry3d tcp = Eigen::Isometry3d::Identity();
            tcp.linear() = q_from.slerp(t, q_to).toRotationMatrix();
            tcp.translation() = from.translation() + t * (to - from.translation());
            const Eigen::Isometry3d f = tcp * head.nozzle(n).tframe.inverse(Eigen::Isometry);
            for (const Nozzle tip : {Nozzle::pla, Nozzle::ccf}) {
                const double z = (f * head.nozzle(tip).tframe.translation()).z();
                if (z < part_top_ + head.idle_clearance_mm) {
                    issue(layer, path, -1,
                          "head switch to " + std::string(to_string(n)) + ": the " +
                              std::string(to_string(tip)) + " nozzle tip comes down to " + mm(z) +
                              ", less than the clearance " + mm(head.idle_clearance_mm) +
                              " above the part top " + mm(part_top_));
                    k = turn_samples;
                    break;
                }
            }
        }
        nozzle_ = n;
        ProgramMove m = travel_move(MoveRole::turn, to, true);
        m.layer = layer;
        m.path = path;
        const std::size_t i = emit(m);
        program_.moves[i].length_mm = (to - from.translation()).norm();
        ++program_.stats.head_switches;
    }

    void check_clearance(const Eigen::Vector3d& tcp, Nozzle n, int layer, int path, int point) {
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.linear() = orientation_[index(n)].toRotationMatrix();
        pose.translation() = tcp;
        const double top = std::max(part_top_, tcp.z());
        const double z = idle_tip_position(cell_.head, n, pose).z();
        const double clearance = cell_.head.idle_clearance_mm;
        if (z - top < clearance - 1e-9)
            issue(layer, path, point,
                  "the idle " + std::string(to_string(other(n))) + " nozzle tip at z " + mm(z) +
                      " is " + mm(z - top) + " above the part top " + mm(top) +
                      ", less than the clearance " + mm(clearance));
    }

    void print_path(const RobotLayer& layer, int p, const PreparedPath& path, bool last) {
        const Nozzle n = layer.nozzle;
        const bool fibre = n == Nozzle::ccf;
        const double speed = fibre ? options_.ccf_speed_mm_s : options_.pla_speed_mm_s;
        const double z = layer.z;
        const auto at = [&](std::size_t i) {
            return Eigen::Vector3d(path.points[i].x(), path.points[i].y(), z);
        };

        std::vector<std::size_t> fixed;
        if (path.cut != no_index) fixed.push_back(path.cut);
        const PointMergeOptions merge{.chord_tolerance_mm = cell_.motion.chord_tolerance_mm,
                                      .min_segment_mm = cell_.motion.min_segment_mm};
        const std::vector<std::size_t> kept = merge_points(path.points, fixed, merge);
        program_.stats.points_merged += path.points.size() - kept.size();
        ++program_.stats.paths;

        travel_to(at(0), n, layer.index, p);
        check_clearance(at(0), n, layer.index, p, 0);

        std::size_t first = no_index, cut_move = no_index;
        for (std::size_t k = 1; k < kept.size(); ++k) {
            const std::size_t i = kept[k];
            ProgramMove m;
            m.role = MoveRole::print;
            m.nozzle = n;
            m.position_mm = at(i);
            m.orientation = orientation_[index(n)];
            m.speed_mm_s = speed;
            m.turn_speed_deg_s = cell_.motion.turn_speed_deg_s;
            m.fine = k + 1 == kept.size();
            m.zone_mm = m.fine ? 0 : cell_.motion.print_zone_mm;
            m.layer = layer.index;
            m.path = p;
            m.point = path.source[i];
            const std::size_t mi = emit(m);
            if (first == no_index) first = mi;
            if (i == path.cut) cut_move = mi;
            check_clearance(m.position_mm, n, layer.index, p, m.point);
        }
        const std::size_t end = program_.moves.size() - 1;
        const Eigen::Vector3d start_point = at(0), end_point = at(kept.back());

        if (!fibre) {
            ProgramEvent& on = event(EventKind::extrude_on, first, EventAnchor::start, start_point,
                                     layer.index, p);
            on.equipment_lag = true;
            on.length_mm = path.length_mm;
            on.speed_mm_s = speed;
            ProgramEvent& off =
                event(EventKind::extrude_off, end, EventAnchor::end, end_point, layer.index, p);
            off.equipment_lag = true;
            off.speed_mm_s = speed;
        } else {
            const double rest = std::min(options_.cutter_distance_mm, path.length_mm);
            ProgramEvent& thread = event(EventKind::fibre_start, first, EventAnchor::before,
                                         start_point, layer.index, p);
            thread.barrier = true;
            thread.length_mm = path.length_mm - rest;
            thread.speed_mm_s = speed;
            ProgramEvent& cut =
                cut_move == no_index
                    ? event(EventKind::cut, first, EventAnchor::start, at(path.cut), layer.index, p)
                    : event(EventKind::cut, cut_move, EventAnchor::end, at(path.cut), layer.index,
                            p);
            cut.equipment_lag = true;
            cut.length_mm = rest;
            cut.speed_mm_s = speed;
            ProgramEvent& done =
                event(EventKind::path_end, end, EventAnchor::end, end_point, layer.index, p);
            done.speed_mm_s = speed;
        }
        part_top_ = std::max(part_top_, z);
        layer_ = layer.index;
        path_ = p;
        if (last) {
            pending_layer_end_ = true;
            pending_layer_ = layer.index;
        }
    }

    void number_events() {
        const auto rank = [](EventAnchor a) {
            return a == EventAnchor::before ? 0 : a == EventAnchor::start ? 1 : 2;
        };
        std::stable_sort(program_.events.begin(), program_.events.end(),
                         [&](const ProgramEvent& a, const ProgramEvent& b) {
                             if (a.move != b.move) return a.move < b.move;
                             return rank(a.anchor) < rank(b.anchor);
                         });
        int seq = 0;
        for (ProgramEvent& e : program_.events) e.sequence = ++seq;
    }

    void compute_stats() {
        ProgramStats& s = program_.stats;
        s.moves = program_.moves.size();
        s.events = program_.events.size();
        double t = 0;
        Eigen::Quaterniond previous = program_.moves.empty() ? Eigen::Quaterniond::Identity()
                                                             : program_.moves.front().orientation;
        for (const ProgramMove& m : program_.moves) {
            double dt = m.speed_mm_s > 0 ? m.length_mm / m.speed_mm_s : 0;
            if (m.role == MoveRole::turn && m.turn_speed_deg_s > 0)
                dt = std::max(dt, previous.angularDistance(m.orientation) * 180 / std::numbers::pi /
                                      m.turn_speed_deg_s);
            previous = m.orientation;
            if (m.fine) {
                ++s.fine_points;
                dt += cell_.motion.fine_allowance_s;
            }
            t += dt;
            if (m.role == MoveRole::print) {
                ++s.print_moves;
                s.print_length_mm += m.length_mm;
            } else {
                ++s.travel_moves;
                s.travel_length_mm += m.length_mm;
            }
        }
        for (const ProgramEvent& e : program_.events) {
            if (!e.barrier) continue;
            ++s.barriers;
            t +=
                e.kind == EventKind::fibre_start ? options_.fibre_thread_s : options_.head_switch_s;
        }
        s.duration_s = t;
    }

    const RobotCellConfig& cell_;
    const ProgramOptions& options_;
    Eigen::Quaterniond orientation_[2];

    PrintProgram program_;
    std::vector<ProgramIssue> issues_;
    bool started_ = false;
    Nozzle nozzle_ = Nozzle::pla;
    Eigen::Vector3d position_ = Eigen::Vector3d::Zero();
    Eigen::Quaterniond rotation_ = Eigen::Quaterniond::Identity();
    double part_top_ = 0;  // highest z printed so far (the bed: 0)
    bool pending_layer_end_ = false;
    int pending_layer_ = -1;
    bool pending_barrier_ = false;
    int layer_ = -1, path_ = -1;  // the last path printed
};

std::string join_messages(const std::vector<ProgramIssue>& issues) {
    constexpr std::size_t shown = 10;
    std::string s = "print program: " + std::to_string(issues.size()) + " problem" +
                    (issues.size() == 1 ? "" : "s");
    for (std::size_t i = 0; i < issues.size() && i < shown; ++i) s += "\n  " + issues[i].message;
    if (issues.size() > shown)
        s += "\n  ... and " + std::to_string(issues.size() - shown) + " more";
    return s;
}

}  // namespace

std::string_view to_string(MoveRole r) {
    switch (r) {
        case MoveRole::start:
            return "start";
        case MoveRole::lift:
            return "lift";
        case MoveRole::travel:
            return "travel";
        case MoveRole::turn:
            return "turn";
        case MoveRole::approach:
            return "approach";
        case MoveRole::print:
            return "print";
    }
    return "?";
}

std::string_view to_string(EventKind k) {
    switch (k) {
        case EventKind::extrude_on:
            return "extrude_on";
        case EventKind::extrude_off:
            return "extrude_off";
        case EventKind::fibre_start:
            return "fibre_start";
        case EventKind::cut:
            return "cut";
        case EventKind::path_end:
            return "path_end";
        case EventKind::layer_end:
            return "layer_end";
        case EventKind::head_switch:
            return "head_switch";
    }
    return "?";
}

PrintProgramError::PrintProgramError(std::vector<ProgramIssue> issues)
    : std::runtime_error(join_messages(issues)), issues_(std::move(issues)) {}

PrintProgram build_print_program(const std::vector<RobotLayer>& layers, const RobotCellConfig& cell,
                                 const ProgramOptions& options) {
    Builder b(cell, options);
    for (const RobotLayer& layer : layers) b.add_layer(layer);
    return b.finish();
}

}  // namespace fibrecell::drivers::abb
