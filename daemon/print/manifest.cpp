#include "daemon/print/manifest.hpp"

#include <openssl/evp.h>

#include <array>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

namespace fibrecell::daemon::print {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

json pose(const Eigen::Isometry3d& t) {
    const Eigen::Quaterniond q(t.linear());
    return {{"position_mm", vec(t.translation())},
            {"quaternion", json::array({q.w(), q.x(), q.y(), q.z()})}};
}

json nozzle(const drivers::abb::NozzleConfig& n) {
    json j = pose(n.tframe);
    j["mass_kg"] = n.mass_kg;
    j["cog_mm"] = vec(n.cog_mm);
    return j;
}

std::string_view cut_method(drivers::CutMethod m) {
    switch (m) {
        case drivers::CutMethod::pin: return "pin";
        case drivers::CutMethod::servo: return "servo";
        case drivers::CutMethod::spindle: return "spindle";
    }
    return "?";
}

void flatten(const json& j, const std::string& prefix, std::map<std::string, json>& out) {
    if (j.is_object() && !j.empty()) {
        for (const auto& [k, v] : j.items()) flatten(v, prefix.empty() ? k : prefix + "." + k, out);
        return;
    }
    out[prefix] = j;
}

std::string read_bytes(const fs::path& p, bool& ok) {
    std::ifstream in(p, std::ios::binary);
    std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ok = static_cast<bool>(in) || in.eof();
    return s;
}

}  // namespace

std::string sha256_hex(std::string_view bytes) {
    std::array<unsigned char, EVP_MAX_MD_SIZE> md{};
    unsigned int n = 0;
    if (EVP_Digest(bytes.data(), bytes.size(), md.data(), &n, EVP_sha256(), nullptr) != 1)
        throw std::runtime_error("sha256: libcrypto failed");
    static constexpr char hex[] = "0123456789abcdef";
    std::string out;
    for (unsigned int i = 0; i < n; ++i) {
        out += hex[md[i] >> 4];
        out += hex[md[i] & 15];
    }
    return out;
}

ManifestEntry manifest_entry(std::string path, std::string_view bytes) {
    return {std::move(path), bytes.size(), sha256_hex(bytes)};
}

json cell_facts(const CellConfig& cell) {
    const auto& r = cell.robot;
    const auto& x = cell.extruder;
    const auto model = r.model();
    json robot = {
        {"variant", std::string(model.name)},
        {"kinematics",
         {{"cfx", r.solver.cfx},
          {"limit_margin_deg", r.solver.limit_margin_deg},
          {"wrist_margin_deg", r.solver.wrist_margin_deg},
          {"elbow_margin_deg", r.solver.elbow_margin_deg},
          {"shoulder_margin_mm", r.solver.shoulder_margin_mm}}},
        {"bed", pose(r.bed)},
        {"head",
         {{"pla", nozzle(r.head.pla)},
          {"ccf", nozzle(r.head.ccf)},
          {"tilt_axis", vec(r.head.tilt_axis)},
          {"tilt_deg", r.head.tilt_deg},
          {"yaw_deg", r.head.yaw_deg},
          {"idle_clearance_mm", r.head.idle_clearance_mm}}},
        {"motion",
         {{"max_travel_speed_mm_s", r.motion.max_travel_speed_mm_s},
          {"approach_speed_mm_s", r.motion.approach_speed_mm_s},
          {"turn_speed_deg_s", r.motion.turn_speed_deg_s},
          {"print_zone_mm", r.motion.print_zone_mm},
          {"travel_zone_mm", r.motion.travel_zone_mm},
          {"safe_height_mm", r.motion.safe_height_mm},
          {"head_switch_height_mm", r.motion.head_switch_height_mm},
          {"chord_tolerance_mm", r.motion.chord_tolerance_mm},
          {"min_segment_mm", r.motion.min_segment_mm},
          {"fine_allowance_s", r.motion.fine_allowance_s}}},
        {"rapid",
         {{"max_chunk_lines", r.rapid.max_chunk_lines},
          {"trigger_lag_s", r.rapid.trigger_lag_s},
          {"confl", r.rapid.confl}}},
        {"signals",
         {{"event", r.signals.event},
          {"barrier", r.signals.barrier},
          {"release", r.signals.release},
          {"pause", r.signals.pause},
          {"abort", r.signals.abort},
          {"heartbeat_in", r.signals.heartbeat_in},
          {"heartbeat_out", r.signals.heartbeat_out},
          {"running", r.signals.running}}}};
    json extruder = {
        {"pla",
         {{"tool", x.pla_tool},
          {"nozzle_diameter_mm", x.pla_nozzle_diameter_mm},
          {"max_temp_c", x.pla_max_temp_c},
          {"filament_diameter_mm", x.filament_diameter_mm},
          {"retract_mm", x.retract_mm},
          {"retract_speed_mm_s", x.retract_speed_mm_s}}},
        {"ccf",
         {{"tool", x.ccf_tool},
          {"nozzle_diameter_mm", x.ccf_nozzle_diameter_mm},
          {"max_temp_c", x.ccf_max_temp_c},
          {"cutter_distance_mm", x.cutter_distance_mm},
          {"thread_speed_mm_s", x.thread_speed_mm_s}}},
        {"cutter",
         {{"method", cut_method(x.cutter.method)},
          {"pin", x.cutter.pin},
          {"servo_index", x.cutter.servo_index},
          {"cut_angle_deg", x.cutter.cut_angle_deg},
          {"open_angle_deg", x.cutter.open_angle_deg},
          {"hold_ms", x.cutter.hold_ms}}},
        {"min_extrude_temp_c", x.min_extrude_temp_c},
        {"max_extrusion_length_mm", x.max_extrusion_length_mm},
        {"max_feed_mm_s", x.max_feed_mm_s}};
    return {{"robot", robot}, {"extruder", extruder}};
}

std::vector<std::string> changed_facts(const json& planned, const json& now) {
    std::map<std::string, json> a, b;
    flatten(planned, "", a);
    flatten(now, "", b);
    std::vector<std::string> out;
    for (const auto& [key, was] : a) {
        const auto it = b.find(key);
        if (it == b.end())
            out.push_back(key + ": " + was.dump() + " when planned, not a fact of this cell now");
        else if (it->second != was)
            out.push_back(key + ": " + was.dump() + " when planned, " + it->second.dump() + " now");
    }
    for (const auto& [key, is] : b)
        if (!a.contains(key)) out.push_back(key + ": " + is.dump() + " now, unknown when planned");
    return out;
}

std::string manifest_json_text(const Manifest& m) {
    json files = json::array();
    for (const ManifestEntry& e : m.files)
        files.push_back({{"path", e.path}, {"bytes", e.bytes}, {"sha256", e.sha256}});
    const json j = {{"format", manifest_format},
                    {"job", m.job},
                    {"planned_at", m.planned_at},
                    {"cell", m.cell},
                    {"files", files}};
    return j.dump(2) + "\n";
}

Manifest read_manifest(const fs::path& plan_dir) {
    const fs::path path = plan_dir / manifest_name;
    if (!fs::exists(path))
        throw PlanRefused("the plan has no manifest.json: it is incomplete (planning was cut short, "
                          "or an older fibrecell made it); replan the job");
    bool ok = false;
    const std::string text = read_bytes(path, ok);
    const json j = json::parse(text, nullptr, false);
    const auto damaged = [&](const std::string& why) {
        return PlanRefused("the plan is damaged: " + path.string() + ": " + why + "; replan the job");
    };
    if (!ok || j.is_discarded() || !j.is_object()) throw damaged("not readable JSON");
    if (j.value("format", "") != manifest_format)
        throw damaged("format is not " + std::string(manifest_format));
    Manifest m;
    m.job = j.value("job", "");
    m.planned_at = j.value("planned_at", "");
    m.cell = j.value("cell", json::object());
    if (!j.contains("files") || !j["files"].is_array()) throw damaged("no files list");
    for (const json& f : j["files"]) {
        if (!f.is_object() || !f.contains("path") || !f["path"].is_string() ||
            !f.contains("bytes") || !f["bytes"].is_number_unsigned() || !f.contains("sha256") ||
            !f["sha256"].is_string())
            throw damaged("a files entry without path, bytes and sha256");
        m.files.push_back({f["path"].get<std::string>(), f["bytes"].get<std::uint64_t>(),
                           f["sha256"].get<std::string>()});
    }
    return m;
}

std::vector<std::string> verify_files(const fs::path& plan_dir, const Manifest& m) {
    std::vector<std::string> problems;
    for (const ManifestEntry& e : m.files) {
        const fs::path p = plan_dir / e.path;
        if (!fs::is_regular_file(p)) {
            problems.push_back(e.path + ": missing");
            continue;
        }
        bool ok = false;
        const std::string bytes = read_bytes(p, ok);
        if (!ok)
            problems.push_back(e.path + ": cannot be read");
        else if (bytes.size() != e.bytes)
            problems.push_back(e.path + ": " + std::to_string(bytes.size()) + " bytes, the manifest says " +
                               std::to_string(e.bytes));
        else if (sha256_hex(bytes) != e.sha256)
            problems.push_back(e.path + ": sha256 differs from the manifest");
    }
    return problems;
}

Manifest check_plan(const fs::path& plan_dir, const CellConfig& cell) {
    Manifest m = read_manifest(plan_dir);
    const auto join = [](const std::vector<std::string>& lines) {
        std::string s;
        for (std::size_t i = 0; i < lines.size() && i < 8; ++i) s += (i ? "; " : "") + lines[i];
        if (lines.size() > 8) s += "; and " + std::to_string(lines.size() - 8) + " more";
        return s;
    };
    if (const auto bad = verify_files(plan_dir, m); !bad.empty())
        throw PlanRefused("the plan is damaged (" + join(bad) + "); replan the job");
    if (const auto changed = changed_facts(m.cell, cell_facts(cell)); !changed.empty())
        throw PlanRefused("the cell changed since the job was planned (" + join(changed) +
                          "); replan the job to print it on this cell");
    return m;
}

}  // namespace fibrecell::daemon::print
