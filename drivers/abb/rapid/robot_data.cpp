#include "drivers/abb/rapid/robot_data.hpp"

#include <cmath>

namespace fibrecell::drivers::abb::rapid {
namespace {

// The shapes below are checked by has_shape() first; these read items by position.
double num_at(const Value& v, std::size_t i) {
    return v.items()[i].num();
}
const Value& at(const Value& v, std::size_t i) {
    return v.items()[i];
}

Eigen::Vector3d read_pos(const Value& v) {
    return {num_at(v, 0), num_at(v, 1), num_at(v, 2)};
}
Eigen::Quaterniond read_orient(const Value& v) {
    return {num_at(v, 0), num_at(v, 1), num_at(v, 2), num_at(v, 3)};  // w, x, y, z
}
std::array<double, 6> read_six(const Value& v) {
    std::array<double, 6> out{};
    for (std::size_t i = 0; i < 6; ++i) out[i] = num_at(v, i);
    return out;
}
Pose read_pose(const Value& v) {
    return {read_pos(at(v, 0)), read_orient(at(v, 1))};
}
LoadData read_load(const Value& v) {
    return {num_at(v, 0),
            read_pos(at(v, 1)),
            read_orient(at(v, 2)),
            {num_at(v, 3), num_at(v, 4), num_at(v, 5)}};
}

// Confdata quadrants must be integers that fit an int.
std::optional<int> to_int(double v) {
    if (!std::isfinite(v) || v != std::trunc(v) || std::fabs(v) > 1e6) return std::nullopt;
    return static_cast<int>(v);
}

Value nums(std::initializer_list<double> values, std::string type) {
    Value::Items items;
    for (double v : values) items.push_back(num_value(v));
    return items_value(std::move(items), std::move(type));
}
Value pos_value(const Eigen::Vector3d& p) {
    return nums({p.x(), p.y(), p.z()}, "pos");
}
Value orient_value(const Eigen::Quaterniond& q) {
    return nums({q.w(), q.x(), q.y(), q.z()}, "orient");
}
Value six(const std::array<double, 6>& a, std::string type) {
    return nums({a[0], a[1], a[2], a[3], a[4], a[5]}, std::move(type));
}

}  // namespace

std::optional<Pose> to_pose(const Value& v) {
    if (!has_shape(v, "pose")) return std::nullopt;
    const Value* c = &v;
    return read_pose(*c);
}

std::optional<Robtarget> to_robtarget(const Value& v) {
    if (!has_shape(v, "robtarget")) return std::nullopt;
    const Value* c = &v;
    Robtarget t;
    t.trans_mm = read_pos(at(*c, 0));
    t.rot = read_orient(at(*c, 1));
    const Value& conf = at(*c, 2);
    const auto cf1 = to_int(num_at(conf, 0)), cf4 = to_int(num_at(conf, 1)),
               cf6 = to_int(num_at(conf, 2)), cfx = to_int(num_at(conf, 3));
    if (!cf1 || !cf4 || !cf6 || !cfx) return std::nullopt;
    t.conf = {*cf1, *cf4, *cf6, *cfx};
    t.extax = read_six(at(*c, 3));
    return t;
}

std::optional<JointTarget> to_jointtarget(const Value& v) {
    if (!has_shape(v, "jointtarget")) return std::nullopt;
    const Value* c = &v;
    return JointTarget{read_six(at(*c, 0)), read_six(at(*c, 1))};
}

std::optional<LoadData> to_loaddata(const Value& v) {
    if (!has_shape(v, "loaddata")) return std::nullopt;
    const Value* c = &v;
    return read_load(*c);
}

std::optional<ToolData> to_tooldata(const Value& v) {
    if (!has_shape(v, "tooldata")) return std::nullopt;
    const Value* c = &v;
    return ToolData{at(*c, 0).boolean(), read_pose(at(*c, 1)), read_load(at(*c, 2))};
}

std::optional<WobjData> to_wobjdata(const Value& v) {
    if (!has_shape(v, "wobjdata")) return std::nullopt;
    const Value* c = &v;
    return WobjData{at(*c, 0).boolean(), at(*c, 1).boolean(), at(*c, 2).string(),
                    read_pose(at(*c, 3)), read_pose(at(*c, 4))};
}

std::optional<SpeedData> to_speeddata(const Value& v) {
    if (!has_shape(v, "speeddata")) return std::nullopt;
    const Value* c = &v;
    return SpeedData{num_at(*c, 0), num_at(*c, 1), num_at(*c, 2), num_at(*c, 3)};
}

std::optional<ZoneData> to_zonedata(const Value& v) {
    if (!has_shape(v, "zonedata")) return std::nullopt;
    const Value* c = &v;
    return ZoneData{at(*c, 0).boolean(), num_at(*c, 1), num_at(*c, 2), num_at(*c, 3),
                    num_at(*c, 4),       num_at(*c, 5), num_at(*c, 6)};
}

Value to_value(const Pose& p) {
    return items_value({pos_value(p.trans_mm), orient_value(p.rot)}, "pose");
}

Value to_value(const Robtarget& t) {
    const Value conf = nums({static_cast<double>(t.conf.cf1), static_cast<double>(t.conf.cf4),
                             static_cast<double>(t.conf.cf6), static_cast<double>(t.conf.cfx)},
                            "confdata");
    return items_value({pos_value(t.trans_mm), orient_value(t.rot), conf, six(t.extax, "extjoint")},
                       "robtarget");
}

Value to_value(const JointTarget& t) {
    return items_value({six(t.robax_deg, "robjoint"), six(t.extax, "extjoint")}, "jointtarget");
}

Value to_value(const LoadData& l) {
    return items_value({num_value(l.mass_kg), pos_value(l.cog_mm), orient_value(l.aom),
                        num_value(l.inertia_kgm2.x()), num_value(l.inertia_kgm2.y()),
                        num_value(l.inertia_kgm2.z())},
                       "loaddata");
}

Value to_value(const ToolData& t) {
    return items_value({bool_value(t.robhold), to_value(t.tframe), to_value(t.tload)}, "tooldata");
}

Value to_value(const WobjData& w) {
    return items_value({bool_value(w.robhold), bool_value(w.ufprog), string_value(w.ufmec),
                        to_value(w.uframe), to_value(w.oframe)},
                       "wobjdata");
}

Value to_value(const SpeedData& s) {
    return nums({s.v_tcp_mm_s, s.v_ori_deg_s, s.v_leax_mm_s, s.v_reax_deg_s}, "speeddata");
}

Value to_value(const ZoneData& z) {
    Value v = nums({0, z.pzone_tcp_mm, z.pzone_ori_mm, z.pzone_eax_mm, z.zone_ori_deg,
                    z.zone_leax_mm, z.zone_reax_deg},
                   "zonedata");
    v.items()[0] = bool_value(z.finep);
    return v;
}

}  // namespace fibrecell::drivers::abb::rapid
