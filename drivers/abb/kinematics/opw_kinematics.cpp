#include "drivers/abb/kinematics/opw_kinematics.hpp"

#include <algorithm>
#include <cmath>

namespace fibrecell::drivers::abb {
namespace {

// Rz(a) * Ry(b): the arm turns about z (axis 1) then y (axes 2 + 3); the wrist is Rz Ry Rz.
Eigen::Matrix3d rot_zy(double a, double b) {
    const double ca = std::cos(a), sa = std::sin(a), cb = std::cos(b), sb = std::sin(b);
    Eigen::Matrix3d r;
    r << ca * cb, -sa, ca * sb,  //
        sa * cb, ca, sa * sb,    //
        -sb, 0, cb;
    return r;
}

Eigen::Matrix3d rot_z(double a) {
    return rot_zy(a, 0);
}

// a * b, or a^T * b, by hand: an Eigen 3x3 product costs ~10 us in the unoptimised sanitizer
// build the tests run in, this well under 1 us; in Release the two are alike.
Eigen::Matrix3d product(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b,
                        bool transpose_a = false) {
    const double* x = a.data();  // column-major: a(i, k) = x[i + 3 * k]
    const double* y = b.data();
    Eigen::Matrix3d r;
    double* z = r.data();
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            double sum = 0;
            for (int k = 0; k < 3; ++k)
                sum += (transpose_a ? x[k + 3 * i] : x[i + 3 * k]) * y[k + 3 * j];
            z[i + 3 * j] = sum;
        }
    return r;
}

JointVector to_model(const OpwParameters& p, const JointVector& q) {
    JointVector t;
    for (int i = 0; i < 6; ++i) t[i] = p.signs[i] * q[i] - p.offsets[i];
    return t;
}

double upper_arm_length(const OpwParameters& p) {
    return std::hypot(p.a2, p.c3);
}

// Angle of the axis-3 -> wrist-centre line from the upper arm's own axis (a2 against c3).
double upper_arm_skew(const OpwParameters& p) {
    return std::atan2(p.a2, p.c3);
}

// Wrist centre in the frame turned by axis 1 (x forward in the arm plane, y = b), model angles.
Eigen::Vector2d arm_plane_wrist(const OpwParameters& p, const JointVector& t) {
    const double phi = t[1] + t[2];
    return {p.a1 + p.c2 * std::sin(t[1]) + p.a2 * std::cos(phi) + p.c3 * std::sin(phi),
            p.c1 + p.c2 * std::cos(t[1]) - p.a2 * std::sin(phi) + p.c3 * std::cos(phi)};
}

Eigen::Vector3d wrist_centre_model(const OpwParameters& p, const JointVector& t) {
    const Eigen::Vector2d xz = arm_plane_wrist(p, t);
    const double c = std::cos(t[0]), s = std::sin(t[0]);
    return {c * xz.x() - s * p.b, s * xz.x() + c * p.b, xz.y()};
}

}  // namespace

Eigen::Isometry3d forward_kinematics(const OpwParameters& p, const JointVector& q) {
    const JointVector t = to_model(p, q);
    const Eigen::Matrix3d r =
        product(rot_zy(t[0], t[1] + t[2]), product(rot_zy(t[3], t[4]), rot_z(t[5])));
    Eigen::Isometry3d pose;
    pose.linear() = r;
    pose.translation() = wrist_centre_model(p, t) + p.c4 * r.col(2);
    pose.makeAffine();
    return pose;
}

Eigen::Vector3d wrist_centre(const OpwParameters& p, const JointVector& q) {
    return wrist_centre_model(p, to_model(p, q));
}

Eigen::Vector3d wrist_centre(const OpwParameters& p, const Eigen::Isometry3d& tool0) {
    return tool0.translation() - p.c4 * tool0.linear().col(2);
}

std::optional<JointVector> inverse_kinematics(const OpwParameters& p,
                                              const Eigen::Isometry3d& tool0, int branch) {
    const bool behind = (branch & branch_behind_axis1) != 0;
    const bool elbow_behind = (branch & branch_behind_lower_arm) != 0;
    const double sign5 = (branch & branch_wrist_negative) != 0 ? -1 : 1;
    const Eigen::Matrix3d r = tool0.linear();
    const Eigen::Vector3d wc = wrist_centre(p, tool0);

    // Axis 1: turn the arm plane through the wrist centre; behind = facing away from it.
    const double rho2 = wc.x() * wc.x() + wc.y() * wc.y() - p.b * p.b;
    if (rho2 < 0) return std::nullopt;  // only with b != 0: inside the offset circle
    const double x1 = behind ? -std::sqrt(rho2) : std::sqrt(rho2);
    const double t1 = std::atan2(wc.y(), wc.x()) - std::atan2(p.b, x1);

    // Axes 2, 3: triangle lower arm c2, upper arm k, shoulder -> wrist centre (u, v).
    const double u = x1 - p.a1, v = wc.z() - p.c1;
    const double k = upper_arm_length(p);
    double cos_g = (u * u + v * v - p.c2 * p.c2 - k * k) / (2 * p.c2 * k);
    if (std::abs(cos_g) > 1 + 1e-12) return std::nullopt;
    cos_g = std::clamp(cos_g, -1.0, 1.0);
    const double sin_g = (elbow_behind ? -1 : 1) * std::sqrt(1 - cos_g * cos_g);
    const double g = std::atan2(sin_g, cos_g);
    const double t2 = std::atan2(u, v) - std::atan2(k * sin_g, p.c2 + k * cos_g);
    const double t3 = g - upper_arm_skew(p);

    // Wrist: w = Rz(t4) Ry(t5) Rz(t6), the flange relative to the upper arm.
    const Eigen::Matrix3d w = product(rot_zy(t1, t2 + t3), r, true);
    const double s5 = std::hypot(w(0, 2), w(1, 2));
    const double t5 = sign5 * std::atan2(s5, w(2, 2));
    double t4 = 0, t6 = 0;
    if (s5 > 1e-10) {
        t4 = std::atan2(sign5 * w(1, 2), sign5 * w(0, 2));
        t6 = std::atan2(sign5 * w(2, 1), -sign5 * w(2, 0));
    } else {
        // Axes 4 and 6 are aligned: only their sum (or difference) is defined.
        const Eigen::Matrix3d z6 = product(rot_zy(0, t5), w, true);
        t6 = std::atan2(z6(1, 0), z6(0, 0));
    }

    const JointVector t{t1, t2, t3, t4, t5, t6};
    JointVector q;
    for (int i = 0; i < 6; ++i) q[i] = wrap_to_pi(p.signs[i] * (t[i] + p.offsets[i]));
    return q;
}

std::array<std::optional<JointVector>, branch_count> inverse_kinematics(
    const OpwParameters& p, const Eigen::Isometry3d& tool0) {
    std::array<std::optional<JointVector>, branch_count> all;
    for (int b = 0; b < branch_count; ++b) all[b] = inverse_kinematics(p, tool0, b);
    return all;
}

int branch_of(const OpwParameters& p, const JointVector& q) {
    const JointVector t = to_model(p, q);
    int branch = 0;
    if (arm_plane_wrist(p, t).x() < 0) branch |= branch_behind_axis1;
    if (elbow_angle(p, q) < 0) branch |= branch_behind_lower_arm;
    if (wrap_to_pi(t[4]) < 0) branch |= branch_wrist_negative;
    return branch;
}

double elbow_angle(const OpwParameters& p, const JointVector& q) {
    return wrap_to_pi(to_model(p, q)[2] + upper_arm_skew(p));
}

double stretched_arm_joint3(const OpwParameters& p) {
    return wrap_to_pi(p.signs[2] * (-upper_arm_skew(p) + p.offsets[2]));
}

double axis1_distance_mm(const OpwParameters& p, const Eigen::Vector3d& wc) {
    return std::sqrt(std::max(0.0, wc.x() * wc.x() + wc.y() * wc.y() - p.b * p.b));
}

double shoulder_to_wrist_mm(const OpwParameters& p, const Eigen::Vector3d& wc, bool behind_axis1) {
    const double x1 = axis1_distance_mm(p, wc) * (behind_axis1 ? -1 : 1);
    return std::hypot(x1 - p.a1, wc.z() - p.c1);
}

double max_wrist_reach_mm(const OpwParameters& p) {
    return p.c2 + upper_arm_length(p);
}

double min_wrist_reach_mm(const OpwParameters& p) {
    return std::abs(p.c2 - upper_arm_length(p));
}

}  // namespace fibrecell::drivers::abb
