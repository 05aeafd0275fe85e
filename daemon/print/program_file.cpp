#include "daemon/print/program_file.hpp"

#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace fibrecell::daemon::print {
namespace {

namespace abb = drivers::abb;
using nlohmann::json;

constexpr const char* move_columns[] = {
    "role", "nozzle", "joint", "x_mm", "y_mm", "z_mm", "qw", "qx", "qy", "qz", "speed_mm_s",
    "turn_speed_deg_s", "fine", "zone_mm", "length_mm", "layer", "path", "point",
    "j1_rad", "j2_rad", "j3_rad", "j4_rad", "j5_rad", "j6_rad"};
constexpr const char* event_columns[] = {
    "sequence", "kind", "barrier", "equipment_lag", "move", "anchor", "x_mm", "y_mm", "z_mm",
    "nozzle", "layer", "path", "length_mm", "speed_mm_s"};

void append(std::string& out, double v) {
    if (!std::isfinite(v)) throw std::invalid_argument("program.json: a non-finite number");
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
}

void append(std::string& out, long long v) {
    char buf[24];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
}

void append(std::string& out, std::string_view word) {
    out += '"';
    out += word;
    out += '"';
}

std::string_view anchor_name(abb::EventAnchor a) {
    switch (a) {
        case abb::EventAnchor::before: return "before";
        case abb::EventAnchor::start: return "start";
        case abb::EventAnchor::end: return "end";
    }
    return "?";
}

template <class E, std::size_t N>
E parse_word(const json& v, const E (&all)[N], std::string_view (*name)(E), const std::string& where) {
    if (v.is_string())
        for (const E e : all)
            if (name(e) == v.get<std::string>()) return e;
    throw std::invalid_argument(where + ": unknown value " + v.dump());
}

std::string_view nozzle_name(abb::Nozzle n) { return abb::to_string(n); }
std::string_view role_name(abb::MoveRole r) { return abb::to_string(r); }
std::string_view kind_name(abb::EventKind k) { return abb::to_string(k); }

constexpr abb::Nozzle nozzles[] = {abb::Nozzle::pla, abb::Nozzle::ccf};
constexpr abb::MoveRole roles[] = {abb::MoveRole::start, abb::MoveRole::lift, abb::MoveRole::travel,
                                   abb::MoveRole::turn, abb::MoveRole::approach, abb::MoveRole::print};
constexpr abb::EventKind kinds[] = {abb::EventKind::extrude_on, abb::EventKind::extrude_off,
                                    abb::EventKind::fibre_start, abb::EventKind::cut,
                                    abb::EventKind::path_end, abb::EventKind::layer_end,
                                    abb::EventKind::head_switch};
constexpr abb::EventAnchor anchors[] = {abb::EventAnchor::before, abb::EventAnchor::start,
                                        abb::EventAnchor::end};

// Reads the cells of one row in column order, naming the row and column in errors.
class Row {
  public:
    Row(const json& row, std::string where, std::size_t columns) : row_(row), where_(std::move(where)) {
        if (!row.is_array() || row.size() != columns)
            throw std::invalid_argument(where_ + ": " + std::to_string(columns) + " values expected");
    }
    const json& next() { return row_[i_++]; }
    std::string at() const { return where_ + "[" + std::to_string(i_) + "]"; }
    double number() {
        const std::string w = at();
        const json& v = next();
        if (!v.is_number()) throw std::invalid_argument(w + ": a number is expected");
        return v.get<double>();
    }
    long long integer() {
        const std::string w = at();
        const json& v = next();
        if (!v.is_number_integer()) throw std::invalid_argument(w + ": an integer is expected");
        return v.get<long long>();
    }
    bool flag() { return integer() != 0; }
    template <class E, std::size_t N>
    E word(const E (&all)[N], std::string_view (*name)(E)) {
        const std::string w = at();
        return parse_word(next(), all, name, w);
    }

  private:
    const json& row_;
    std::string where_;
    std::size_t i_ = 0;
};

json stats_json(const abb::ProgramStats& s) {
    return {{"moves", s.moves},           {"print_moves", s.print_moves},
            {"travel_moves", s.travel_moves}, {"fine_points", s.fine_points},
            {"events", s.events},         {"barriers", s.barriers},
            {"layers", s.layers},         {"paths", s.paths},
            {"head_switches", s.head_switches}, {"points_in", s.points_in},
            {"points_merged", s.points_merged}, {"print_length_mm", s.print_length_mm},
            {"travel_length_mm", s.travel_length_mm}, {"duration_s", s.duration_s}};
}

abb::ProgramStats stats_from(const json& j) {
    abb::ProgramStats s;
    const auto count = [&](const char* k) { return j.value(k, std::size_t{0}); };
    s.moves = count("moves");
    s.print_moves = count("print_moves");
    s.travel_moves = count("travel_moves");
    s.fine_points = count("fine_points");
    s.events = count("events");
    s.barriers = count("barriers");
    s.layers = count("layers");
    s.paths = count("paths");
    s.head_switches = count("head_switches");
    s.points_in = count("points_in");
    s.points_merged = count("points_merged");
    s.print_length_mm = j.value("print_length_mm", 0.0);
    s.travel_length_mm = j.value("travel_length_mm", 0.0);
    s.duration_s = j.value("duration_s", 0.0);
    return s;
}

json column_names(const auto& names) {
    json a = json::array();
    for (const char* n : names) a.push_back(n);
    return a;
}

}  // namespace

std::string program_json_text(const abb::PrintProgram& program,
                              const std::vector<abb::JointVector>& joints) {
    if (joints.size() != program.moves.size())
        throw std::invalid_argument("program.json: " + std::to_string(joints.size()) +
                                    " joint vectors for " + std::to_string(program.moves.size()) +
                                    " moves");
    std::string out;
    out.reserve(program.moves.size() * 260 + program.events.size() * 120 + 1024);
    out += "{\"format\": \"";
    out += program_format;
    out += "\",\n \"move_columns\": " + column_names(move_columns).dump() + ",\n \"moves\": [";
    for (std::size_t i = 0; i < program.moves.size(); ++i) {
        const abb::ProgramMove& m = program.moves[i];
        out += i == 0 ? "\n  [" : ",\n  [";
        append(out, abb::to_string(m.role));
        out += ',';
        append(out, abb::to_string(m.nozzle));
        out += m.joint ? ",1" : ",0";
        for (const double v : {m.position_mm.x(), m.position_mm.y(), m.position_mm.z(),
                               m.orientation.w(), m.orientation.x(), m.orientation.y(),
                               m.orientation.z(), m.speed_mm_s, m.turn_speed_deg_s}) {
            out += ',';
            append(out, v);
        }
        out += m.fine ? ",1" : ",0";
        for (const double v : {m.zone_mm, m.length_mm}) {
            out += ',';
            append(out, v);
        }
        for (const long long v : {m.layer, m.path, m.point}) {
            out += ',';
            append(out, v);
        }
        for (const double v : joints[i]) {
            out += ',';
            append(out, v);
        }
        out += ']';
    }
    out += "],\n \"event_columns\": " + column_names(event_columns).dump() + ",\n \"events\": [";
    for (std::size_t i = 0; i < program.events.size(); ++i) {
        const abb::ProgramEvent& e = program.events[i];
        out += i == 0 ? "\n  [" : ",\n  [";
        append(out, static_cast<long long>(e.sequence));
        out += ',';
        append(out, abb::to_string(e.kind));
        out += e.barrier ? ",1" : ",0";
        out += e.equipment_lag ? ",1" : ",0";
        out += ',';
        append(out, static_cast<long long>(e.move));
        out += ',';
        append(out, anchor_name(e.anchor));
        for (const double v : {e.position_mm.x(), e.position_mm.y(), e.position_mm.z()}) {
            out += ',';
            append(out, v);
        }
        out += ',';
        append(out, abb::to_string(e.nozzle));
        for (const long long v : {e.layer, e.path}) {
            out += ',';
            append(out, v);
        }
        for (const double v : {e.length_mm, e.speed_mm_s}) {
            out += ',';
            append(out, v);
        }
        out += ']';
    }
    out += "],\n \"warnings\": " + json(program.warnings).dump();
    out += ",\n \"stats\": " + stats_json(program.stats).dump() + "}\n";
    return out;
}

ProgramFile parse_program_json(std::string_view text, const std::string& origin) {
    const json j = json::parse(text, nullptr, false);
    if (j.is_discarded() || !j.is_object())
        throw std::invalid_argument(origin + ": not a JSON object");
    if (j.value("format", "") != program_format)
        throw std::invalid_argument(origin + ": format is not " + std::string(program_format));
    const auto columns_are = [&](const char* key, const auto& names) {
        if (!j.contains(key) || j[key] != column_names(names))
            throw std::invalid_argument(origin + ": " + key + " are not this version's");
    };
    columns_are("move_columns", move_columns);
    columns_are("event_columns", event_columns);
    if (!j.contains("moves") || !j["moves"].is_array() || !j.contains("events") ||
        !j["events"].is_array())
        throw std::invalid_argument(origin + ": moves and events must be lists");

    ProgramFile f;
    const json& moves = j["moves"];
    f.program.moves.reserve(moves.size());
    f.joints.reserve(moves.size());
    for (std::size_t i = 0; i < moves.size(); ++i) {
        Row r(moves[i], origin + ": moves[" + std::to_string(i) + "]", std::size(move_columns));
        abb::ProgramMove m;
        m.role = r.word(roles, role_name);
        m.nozzle = r.word(nozzles, nozzle_name);
        m.joint = r.flag();
        m.position_mm.x() = r.number();
        m.position_mm.y() = r.number();
        m.position_mm.z() = r.number();
        m.orientation.w() = r.number();
        m.orientation.x() = r.number();
        m.orientation.y() = r.number();
        m.orientation.z() = r.number();
        m.speed_mm_s = r.number();
        m.turn_speed_deg_s = r.number();
        m.fine = r.flag();
        m.zone_mm = r.number();
        m.length_mm = r.number();
        m.layer = static_cast<int>(r.integer());
        m.path = static_cast<int>(r.integer());
        m.point = static_cast<int>(r.integer());
        abb::JointVector q{};
        for (double& v : q) v = r.number();
        f.program.moves.push_back(m);
        f.joints.push_back(q);
    }
    const json& events = j["events"];
    f.program.events.reserve(events.size());
    for (std::size_t i = 0; i < events.size(); ++i) {
        const std::string where = origin + ": events[" + std::to_string(i) + "]";
        Row r(events[i], where, std::size(event_columns));
        abb::ProgramEvent e;
        e.sequence = static_cast<int>(r.integer());
        e.kind = r.word(kinds, kind_name);
        e.barrier = r.flag();
        e.equipment_lag = r.flag();
        const long long move = r.integer();
        e.anchor = r.word(anchors, anchor_name);
        e.position_mm.x() = r.number();
        e.position_mm.y() = r.number();
        e.position_mm.z() = r.number();
        e.nozzle = r.word(nozzles, nozzle_name);
        e.layer = static_cast<int>(r.integer());
        e.path = static_cast<int>(r.integer());
        e.length_mm = r.number();
        e.speed_mm_s = r.number();
        if (e.sequence != static_cast<int>(i) + 1)
            throw std::invalid_argument(where + ": sequence " + std::to_string(e.sequence) +
                                        ", expected " + std::to_string(i + 1));
        if (move < 0 || static_cast<std::size_t>(move) >= f.program.moves.size())
            throw std::invalid_argument(where + ": move " + std::to_string(move) +
                                        " is not one of the program's");
        e.move = static_cast<std::size_t>(move);
        f.program.events.push_back(e);
    }
    if (j.contains("warnings") && j["warnings"].is_array())
        for (const json& w : j["warnings"])
            if (w.is_string()) f.program.warnings.push_back(w.get<std::string>());
    if (j.contains("stats") && j["stats"].is_object()) f.program.stats = stats_from(j["stats"]);
    return f;
}

}  // namespace fibrecell::daemon::print
