#include "drivers/abb/cell/robot_config.hpp"

#include "drivers/abb/rapid/names.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace fibrecell::drivers::abb {
namespace {

constexpr double pi = std::numbers::pi;

Eigen::Vector3d to_vector(const std::array<double, 3>& a) {
    return {a[0], a[1], a[2]};
}

// Nozzle `n`'s TCP orientation in the bed frame before the tilt: the nozzle axis (tool z) along
// the bed's -z and the tilt axis along the bed direction yaw_deg.
Eigen::Matrix3d untilted_orientation(const HeadConfig& head, Nozzle n) {
    const Eigen::Matrix3d tool = head.nozzle(n).tframe.linear();  // tool0 -> TCP
    // The tilt axis and the nozzle axis in the TCP frame; the axis is made exactly
    // perpendicular to the nozzle (the loader rejects heads where it is far from it).
    const Eigen::Vector3d z_tcp = Eigen::Vector3d::UnitZ();
    Eigen::Vector3d a_tcp = tool.transpose() * head.tilt_axis;
    a_tcp = (a_tcp - a_tcp.dot(z_tcp) * z_tcp).normalized();
    Eigen::Matrix3d in_tcp;
    in_tcp << a_tcp, z_tcp.cross(a_tcp), z_tcp;
    const double yaw = head.yaw_deg * pi / 180;
    const Eigen::Vector3d a_bed(std::cos(yaw), std::sin(yaw), 0);
    const Eigen::Vector3d z_bed = -Eigen::Vector3d::UnitZ();
    Eigen::Matrix3d in_bed;
    in_bed << a_bed, z_bed.cross(a_bed), z_bed;
    return in_bed * in_tcp.transpose();
}

// The tilt axis in the bed frame (it does not move when the head turns about it).
Eigen::Vector3d tilt_axis_in_bed(const HeadConfig& head) {
    const double yaw = head.yaw_deg * pi / 180;
    return {std::cos(yaw), std::sin(yaw), 0};
}

// Lift of the idle tip over the active one for a signed tilt.
double lift_at(const HeadConfig& head, Nozzle n, double tilt_deg) {
    const Eigen::Matrix3d r =
        Eigen::AngleAxisd(tilt_deg * pi / 180, tilt_axis_in_bed(head)).toRotationMatrix() *
        untilted_orientation(head, n);
    Eigen::Isometry3d tcp = Eigen::Isometry3d::Identity();
    tcp.linear() = r;
    const Eigen::Isometry3d flange = tcp * head.nozzle(n).tframe.inverse(Eigen::Isometry);
    return (flange * head.nozzle(other(n)).tframe.translation()).z();
}

Eigen::Quaterniond read_orientation(config::Section& s, const Eigen::Quaterniond& fallback) {
    const bool rpy = s.has("rpy_deg"), quat = s.has("quaternion");
    if (rpy && quat) s.fail("quaternion", "give either rpy_deg or quaternion, not both");
    if (rpy) {
        const auto a = s.vec3("rpy_deg");
        s.node("quaternion");
        return rpy_deg_to_quaternion(a[0], a[1], a[2]);
    }
    s.node("rpy_deg");
    if (!quat) {
        s.node("quaternion");
        return fallback;
    }
    const auto q = s.get<std::vector<double>>("quaternion");
    if (q.size() != 4) s.fail("quaternion", "must be a list of 4 numbers [w, x, y, z]");
    const Eigen::Quaterniond r(q[0], q[1], q[2], q[3]);
    if (!std::isfinite(r.norm()) || std::abs(r.norm() - 1) > 1e-3)
        s.fail("quaternion", "must have unit length (|q| within 1e-3 of 1)");
    return r.normalized();
}

Eigen::Isometry3d read_pose(config::Section& s, const Eigen::Isometry3d& fallback) {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    const Eigen::Vector3d p = fallback.translation();
    t.translation() = to_vector(s.vec3_or("position_mm", {p.x(), p.y(), p.z()}));
    t.linear() = read_orientation(s, Eigen::Quaterniond(fallback.linear())).toRotationMatrix();
    return t;
}

NozzleConfig read_nozzle(config::Section s, const NozzleConfig& fallback) {
    NozzleConfig n = fallback;
    n.tframe = read_pose(s, fallback.tframe);
    n.mass_kg = s.number("mass_kg", fallback.mass_kg, 0, 20, true);
    n.cog_mm = to_vector(
        s.vec3_or("cog_mm", {fallback.cog_mm.x(), fallback.cog_mm.y(), fallback.cog_mm.z()}));
    s.finish();
    return n;
}

std::string signal_name(config::Section& s, std::string_view key, const std::string& fallback) {
    const std::string v = s.get_or<std::string>(key, fallback);
    if (!rapid::is_identifier(v) || v.size() > rapid::max_identifier_length ||
        rapid::is_reserved_word(v))
        s.fail(key,
               "must be a RAPID name (a letter, then letters, digits or _, at most 32, not "
               "a reserved word)");
    return v;
}

}  // namespace

std::string_view to_string(Nozzle n) {
    return n == Nozzle::pla ? "pla" : "ccf";
}

Eigen::Isometry3d HeadConfig::default_tframe(double y_mm) {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear() = rpy_deg_to_quaternion(0, 90, 0).toRotationMatrix();  // tool z = tool0 +x
    t.translation() = Eigen::Vector3d(95, y_mm, 60);
    return t;
}

Eigen::Isometry3d RobotCellConfig::default_bed() {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.translation() = Eigen::Vector3d(380, -150, 100);
    return t;
}

std::vector<std::string> RobotSignals::all() const {
    return {event, barrier, release, pause, abort, heartbeat_in, heartbeat_out, running};
}

TcpFrames RobotCellConfig::frames(Nozzle n) const {
    return {.tool = head.nozzle(n).tframe, .work_object = bed};
}

Eigen::Quaterniond rpy_deg_to_quaternion(double roll_deg, double pitch_deg, double yaw_deg) {
    const auto r = [](double deg, const Eigen::Vector3d& axis) {
        return Eigen::AngleAxisd(deg * pi / 180, axis);
    };
    return Eigen::Quaterniond(r(yaw_deg, Eigen::Vector3d::UnitZ()) *
                              r(pitch_deg, Eigen::Vector3d::UnitY()) *
                              r(roll_deg, Eigen::Vector3d::UnitX()))
        .normalized();
}

double nozzle_tilt_deg(const HeadConfig& head, Nozzle n) {
    return lift_at(head, n, head.tilt_deg) >= lift_at(head, n, -head.tilt_deg) ? head.tilt_deg
                                                                               : -head.tilt_deg;
}

Eigen::Quaterniond print_orientation(const HeadConfig& head, Nozzle n) {
    const Eigen::AngleAxisd tilt(nozzle_tilt_deg(head, n) * pi / 180, tilt_axis_in_bed(head));
    return Eigen::Quaterniond(tilt.toRotationMatrix() * untilted_orientation(head, n)).normalized();
}

Eigen::Vector3d idle_tip_position(const HeadConfig& head, Nozzle active,
                                  const Eigen::Isometry3d& tcp_in_bed) {
    const Eigen::Isometry3d flange =
        tcp_in_bed * head.nozzle(active).tframe.inverse(Eigen::Isometry);
    return flange * head.nozzle(other(active)).tframe.translation();
}

double idle_lift_mm(const HeadConfig& head, Nozzle n) {
    return lift_at(head, n, nozzle_tilt_deg(head, n));
}

RobotCellConfig load_robot_config(config::Section s) {
    RobotCellConfig c;
    {
        const std::string v = s.choice(
            "variant", "7/0.7",
            {"7/0.7", "5/0.9", "IRB 1200-7/0.7", "IRB 1200-5/0.9", "irb1200_7_70", "irb1200_5_90"});
        c.variant = *parse_irb1200_variant(v);
    }
    {
        config::Section k = s.section("kinematics");
        c.solver.cfx = k.integer("cfx", 1, 0, 7);
        c.solver.limit_margin_deg = k.number("limit_margin_deg", 2, 0, 30);
        c.solver.wrist_margin_deg = k.number("wrist_margin_deg", 5, 0, 45);
        c.solver.elbow_margin_deg = k.number("elbow_margin_deg", 5, 0, 45);
        c.solver.shoulder_margin_mm = k.number("shoulder_margin_mm", 50, 0, 500);
        k.finish();
    }
    {
        config::Section b = s.section("bed");
        c.bed = read_pose(b, RobotCellConfig::default_bed());
        b.finish();
    }
    {
        config::Section h = s.section("head");
        auto& hd = c.head;
        hd.pla = read_nozzle(h.section("pla"), hd.pla);
        hd.ccf = read_nozzle(h.section("ccf"), hd.ccf);
        const Eigen::Vector3d axis = to_vector(h.vec3_or("tilt_axis", {0, 0, 1}));
        if (axis.norm() < 1e-9) h.fail("tilt_axis", "must not be the zero vector");
        hd.tilt_axis = axis.normalized();
        hd.tilt_deg = h.number("tilt_deg", 15, 0, 45, true);
        hd.yaw_deg = h.number("yaw_deg", 0, -360, 360);
        hd.idle_clearance_mm = h.number("idle_clearance_mm", 3, 0, 100);
        for (const Nozzle n : {Nozzle::pla, Nozzle::ccf}) {
            const Eigen::Vector3d z = hd.nozzle(n).tframe.linear().col(2);
            const double off_deg =
                std::abs(std::asin(std::clamp(z.dot(hd.tilt_axis), -1.0, 1.0))) * 180 / pi;
            if (off_deg > 0.5) {
                std::ostringstream m;
                m << "the " << to_string(n) << " nozzle axis (tool z) is " << off_deg
                  << " deg off perpendicular to the tilt axis; a tilt about the axis would not "
                     "tilt it (at most 0.5 deg)";
                h.fail("tilt_axis", m.str());
            }
        }
        h.finish();
        for (const Nozzle n : {Nozzle::pla, Nozzle::ccf}) {
            const double lift = idle_lift_mm(hd, n);
            if (lift < hd.idle_clearance_mm) {
                std::ostringstream m;
                m << "while the " << to_string(n) << " nozzle prints, the " << hd.tilt_deg
                  << " deg tilt lifts the idle nozzle by " << lift
                  << " mm, less than idle_clearance_mm " << hd.idle_clearance_mm;
                s.fail("head", m.str());
            }
        }
    }
    {
        config::Section m = s.section("motion");
        auto& mo = c.motion;
        if (m.has("travel_speed_mm_s"))
            m.fail("travel_speed_mm_s",
                   "the travel speed is the job's (process.pla/ccf.travel_speed_mm_s); the cell "
                   "limits it with max_travel_speed_mm_s");
        mo.max_travel_speed_mm_s = m.number("max_travel_speed_mm_s", 250, 0, 1000, true);
        mo.approach_speed_mm_s = m.number("approach_speed_mm_s", 20, 0, 1000, true);
        mo.turn_speed_deg_s = m.number("turn_speed_deg_s", 60, 0, 500, true);
        mo.print_zone_mm = m.number("print_zone_mm", 0.3, 0, 50);
        mo.travel_zone_mm = m.number("travel_zone_mm", 5, 0, 200);
        mo.safe_height_mm = m.number("safe_height_mm", 5, 0.5, 500);
        mo.head_switch_height_mm = m.number("head_switch_height_mm", 20, 0.5, 500);
        mo.chord_tolerance_mm = m.number("chord_tolerance_mm", 0.02, 0, 1);
        mo.min_segment_mm = m.number("min_segment_mm", 0.3, 0, 10);
        mo.fine_allowance_s = m.number("fine_allowance_s", 0.2, 0, 10);
        m.finish();
    }
    {
        config::Section r = s.section("rapid");
        c.rapid.max_chunk_lines = r.integer("max_chunk_lines", 5000, 40, 100000);
        c.rapid.trigger_lag_s = r.number("trigger_lag_s", 0.05, 0, 1);
        c.rapid.confl = r.get_or<bool>("confl", false);
        r.finish();
    }
    {
        config::Section g = s.section("signals");
        auto& sg = c.signals;
        sg.event = signal_name(g, "event", sg.event);
        sg.barrier = signal_name(g, "barrier", sg.barrier);
        sg.release = signal_name(g, "release", sg.release);
        sg.pause = signal_name(g, "pause", sg.pause);
        sg.abort = signal_name(g, "abort", sg.abort);
        sg.heartbeat_in = signal_name(g, "heartbeat_in", sg.heartbeat_in);
        sg.heartbeat_out = signal_name(g, "heartbeat_out", sg.heartbeat_out);
        sg.running = signal_name(g, "running", sg.running);
        g.finish();
    }
    s.finish();
    return c;
}

}  // namespace fibrecell::drivers::abb
