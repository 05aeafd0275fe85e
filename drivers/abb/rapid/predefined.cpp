#include "drivers/abb/rapid/predefined.hpp"

#include <functional>
#include <map>
#include <numbers>
#include <string>

#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/robot_data.hpp"

namespace fibrecell::drivers::abb::rapid {
namespace {

// v5 ... v7000 all use [v, 500, 5000, 1000] (abb_motion_program_exec rapid_types.py) [S].
constexpr double speeds_mm_s[] = {5,    10,   20,   30,   40,   50,   60,  80,   100,
                                  150,  200,  300,  400,  500,  600,  800, 1000, 1500,
                                  2000, 2500, 3000, 4000, 5000, 6000, 7000};
// vmax depends on the robot in RobotWare; 5000 mm/s is a placeholder for checks only [K].
constexpr double vmax_mm_s = 5000;

struct Zone {
    std::string_view name;
    ZoneData data;
};
// zonedata [finep, pzone_tcp, pzone_ori, pzone_eax, zone_ori, zone_leax, zone_reax] [S].
const Zone zones[] = {
    {"fine", {true, 0, 0, 0, 0, 0, 0}},
    {"z0", {false, 0.3, 0.3, 0.3, 0.03, 0.3, 0.03}},
    {"z1", {false, 1, 1, 1, 0.1, 1, 0.1}},
    {"z5", {false, 5, 8, 8, 0.8, 8, 0.8}},
    {"z10", {false, 10, 15, 15, 1.5, 15, 1.5}},
    {"z15", {false, 15, 23, 23, 2.3, 23, 2.3}},
    {"z20", {false, 20, 30, 30, 3.0, 30, 3.0}},
    {"z30", {false, 30, 45, 45, 4.5, 45, 4.5}},
    {"z40", {false, 40, 60, 60, 6.0, 60, 6.0}},
    {"z50", {false, 50, 75, 75, 7.5, 75, 7.5}},
    {"z60", {false, 60, 90, 90, 9.0, 90, 9.0}},
    {"z80", {false, 80, 120, 120, 12, 120, 12}},
    {"z100", {false, 100, 150, 150, 15, 150, 15}},
    {"z150", {false, 150, 225, 225, 23, 225, 23}},
    {"z200", {false, 200, 300, 300, 30, 300, 30}},
};

// The system's load0 and tool0 load: 1 g at 1 µm, so that the mass is never zero [K].
LoadData load0() {
    return {0.001, {0, 0, 0.001}, Eigen::Quaterniond::Identity(), {0, 0, 0}};
}

using Table = std::map<std::string, PredefinedData, std::less<>>;

// Built once: the validator looks names up here for every name it resolves.
Table build_table() {
    Table t;
    for (double v : speeds_mm_s)
        t.emplace("v" + format_num(v),
                  PredefinedData{"speeddata", true, to_value(SpeedData{v, 500, 5000, 1000})});
    t.emplace("vmax",
              PredefinedData{"speeddata", true, to_value(SpeedData{vmax_mm_s, 500, 5000, 1000})});
    for (const Zone& z : zones)
        t.emplace(std::string(z.name), PredefinedData{"zonedata", true, to_value(z.data)});
    t.emplace("tool0", PredefinedData{"tooldata", false, to_value(ToolData{true, {}, load0()})});
    t.emplace("wobj0", PredefinedData{"wobjdata", false, to_value(WobjData{})});
    t.emplace("load0", PredefinedData{"loaddata", false, to_value(load0())});
    t.emplace("pi", PredefinedData{"num", true, num_value(std::numbers::pi)});
    // Mass-storage names used in Load/StartLoad paths [K].
    t.emplace("diskhome", PredefinedData{"string", true, string_value("HOME:")});
    t.emplace("diskram", PredefinedData{"string", true, string_value("RAMDISK:")});
    t.emplace("disktemp", PredefinedData{"string", true, string_value("TEMP:")});
    return t;
}

const Table& table() {
    static const Table t = build_table();
    return t;
}

}  // namespace

const PredefinedData* predefined_data(std::string_view name) {
    if (name.empty() || name.size() > 8) return nullptr;  // longest: "diskhome"
    const auto it = table().find(fold(name));
    return it == table().end() ? nullptr : &it->second;
}

bool is_predefined_data(std::string_view name) {
    return !name.empty() && name.size() <= 8 && table().count(fold(name)) > 0;
}

}  // namespace fibrecell::drivers::abb::rapid
