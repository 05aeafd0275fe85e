#include "drivers/abb/modbus/robot_io_config.hpp"

#include <functional>
#include <stdexcept>
#include <vector>

namespace fibrecell::drivers::abb {
namespace {

// What a signal is, which decides the tables it may use.
enum class Role { input_word, input_bit, output_word, output_bit };

struct SignalRef {
    const char* name;
    Role role;
    std::function<ModbusAddress*(RobotIoMap&)> get;
};

std::vector<SignalRef> signals() {
    return {
        {"event_number", Role::input_word, [](RobotIoMap& m) { return &m.event_number; }},
        {"barrier_number", Role::input_word, [](RobotIoMap& m) { return &m.barrier_number; }},
        {"robot_running", Role::input_bit, [](RobotIoMap& m) { return &m.robot_running; }},
        {"heartbeat_in", Role::input_bit, [](RobotIoMap& m) { return &m.heartbeat_in; }},
        {"barrier_release", Role::output_word, [](RobotIoMap& m) { return &m.barrier_release; }},
        {"pause_request", Role::output_bit, [](RobotIoMap& m) { return &m.pause_request; }},
        {"abort_request", Role::output_bit, [](RobotIoMap& m) { return &m.abort_request; }},
        {"heartbeat_out", Role::output_bit, [](RobotIoMap& m) { return &m.heartbeat_out; }},
        {"chunk_ready", Role::output_word,
         [](RobotIoMap& m) { return m.chunk_ready ? &*m.chunk_ready : nullptr; }},
    };
}

const char* allowed_tables(Role r) {
    switch (r) {
        case Role::input_word:
            return "input_register or holding_register";
        case Role::input_bit:
            return "discrete_input or coil (or input_register/holding_register with a bit)";
        case Role::output_word:
            return "holding_register";
        case Role::output_bit:
            return "coil";
    }
    return "?";
}

// The problem with one signal's address, or "" when it is fine.
std::string address_problem(Role role, const ModbusAddress& a) {
    if (a.address < 0 || a.address > 65535) return "address must be in [0, 65535]";
    const bool bit_table = is_bit_table(a.table);
    bool ok = false;
    switch (role) {
        case Role::input_word:
            ok = !bit_table && !a.bit;
            break;
        case Role::input_bit:
            ok = bit_table ? !a.bit : a.bit.has_value();
            break;
        case Role::output_word:
            ok = a.table == ModbusTable::holding_register && !a.bit;
            break;
        case Role::output_bit:
            ok = a.table == ModbusTable::coil && !a.bit;
            break;
    }
    if (a.bit && (*a.bit < 0 || *a.bit > 15)) return "bit must be in [0, 15]";
    if (!ok)
        return "table '" + std::string(to_string(a.table)) + "'" + (a.bit ? " with a bit" : "") +
               " cannot carry this signal: use " + allowed_tables(role);
    return "";
}

struct MapProblem {
    std::string signal;
    std::string problem;
};

std::optional<MapProblem> map_problem(const RobotIoMap& map) {
    RobotIoMap m = map;
    struct Seen {
        std::string signal;
        ModbusAddress a;
    };
    std::vector<Seen> seen;
    for (const auto& s : signals()) {
        const ModbusAddress* a = s.get(m);
        if (!a) continue;
        if (auto p = address_problem(s.role, *a); !p.empty()) return MapProblem{s.name, p};
        for (const auto& other : seen) {
            const bool same_word = other.a.table == a->table && other.a.address == a->address;
            // Two bits of one register may share it; anything else on one address collides.
            if (same_word && !(other.a.bit && a->bit && *other.a.bit != *a->bit))
                return MapProblem{s.name, describe(*a) + " is already used by " + other.signal};
        }
        seen.push_back({s.name, *a});
    }
    return std::nullopt;
}

ModbusTable parse_table(config::Section& e, ModbusTable fallback) {
    const std::string t =
        e.choice("table", std::string(to_string(fallback)),
                 {"coil", "discrete_input", "holding_register", "input_register"});
    if (t == "coil") return ModbusTable::coil;
    if (t == "discrete_input") return ModbusTable::discrete_input;
    if (t == "holding_register") return ModbusTable::holding_register;
    return ModbusTable::input_register;
}

}  // namespace

std::string_view to_string(ModbusTable t) {
    switch (t) {
        case ModbusTable::coil:
            return "coil";
        case ModbusTable::discrete_input:
            return "discrete_input";
        case ModbusTable::holding_register:
            return "holding_register";
        case ModbusTable::input_register:
            return "input_register";
    }
    return "?";
}

bool is_bit_table(ModbusTable t) {
    return t == ModbusTable::coil || t == ModbusTable::discrete_input;
}

std::string describe(const ModbusAddress& a) {
    std::string t(to_string(a.table));
    for (auto& c : t)
        if (c == '_') c = ' ';
    std::string s = t + " " + std::to_string(a.address);
    if (a.bit) s += " bit " + std::to_string(*a.bit);
    return s;
}

RobotIoConfig load_robot_io_config(config::Section s) {
    using std::chrono::milliseconds;
    RobotIoConfig c;
    c.host = s.get_or<std::string>("host", c.host);
    if (c.host.empty()) s.fail("host", "must not be empty");
    c.port = s.integer("port", c.port, 1, 65535);
    c.unit_id = s.integer("unit_id", c.unit_id, 0, 255);
    if (c.unit_id > 247 && c.unit_id != 255)
        s.fail("unit_id", "must be in [0, 247] or 255, got " + std::to_string(c.unit_id));
    const double poll_ms = s.number("poll_period_ms", 2.0, 0.1, 1000);
    c.poll_period = std::chrono::microseconds(static_cast<long long>(poll_ms * 1000.0 + 0.5));
    c.response_timeout = milliseconds(s.integer("response_timeout_ms", 250, 1, 60000));
    c.heartbeat_period = milliseconds(s.integer("heartbeat_period_ms", 100, 10, 10000));
    c.robot_heartbeat_timeout =
        milliseconds(s.integer("robot_heartbeat_timeout_ms", 1000, 10, 60000));
    if (c.robot_heartbeat_timeout <= c.poll_period)
        s.fail("robot_heartbeat_timeout_ms", "must be longer than poll_period_ms");
    c.stable_reads = s.integer("stable_reads", 2, 1, 10);
    c.reconnect_backoff_min = milliseconds(s.integer("reconnect_backoff_min_ms", 100, 1, 600000));
    c.reconnect_backoff_max = milliseconds(s.integer("reconnect_backoff_max_ms", 5000, 1, 600000));
    if (c.reconnect_backoff_max < c.reconnect_backoff_min)
        s.fail("reconnect_backoff_max_ms", "must be at least reconnect_backoff_min_ms");
    c.pause_on_fault = s.get_or<bool>("pause_on_fault", true);
    c.service_watchdog = milliseconds(s.integer("service_watchdog_ms", 0, 0, 60000));
    if (c.service_watchdog.count() > 0 && c.service_watchdog <= c.heartbeat_period)
        s.fail("service_watchdog_ms", "must be 0 (off) or longer than heartbeat_period_ms");
    c.stats_log_period = std::chrono::seconds(s.integer("stats_log_period_s", 60, 0, 86400));

    config::Section m = s.section("map");
    for (const auto& sig : signals()) {
        if (!m.has(sig.name)) {
            m.node(sig.name);  // mark as read: the default stays
            continue;
        }
        config::Section e = m.section(sig.name);
        ModbusAddress* target = sig.get(c.map);
        if (!target) {  // an optional signal the YAML switches on
            c.map.chunk_ready = ModbusAddress{ModbusTable::holding_register, 0, std::nullopt};
            target = &*c.map.chunk_ready;
        }
        ModbusAddress a;
        a.table = parse_table(e, target->table);
        if (!e.has("address")) e.fail("address", "is required");
        a.address = e.integer("address", 0, 0, 65535);
        if (e.has("bit")) a.bit = e.integer("bit", 0, 0, 15);
        e.node("bit");
        e.finish();
        if (auto p = address_problem(sig.role, a); !p.empty()) m.fail(sig.name, p);
        *target = a;
    }
    m.finish();
    if (auto p = map_problem(c.map)) m.fail(p->signal, p->problem);
    s.finish();
    return c;
}

void validate(const RobotIoConfig& c) {
    auto bad = [](const std::string& what) { throw std::invalid_argument("robot_io: " + what); };
    if (c.host.empty()) bad("host must not be empty");
    if (c.port < 1 || c.port > 65535) bad("port must be in [1, 65535]");
    if (c.unit_id < 0 || (c.unit_id > 247 && c.unit_id != 255))
        bad("unit_id must be in [0, 247] or 255");
    if (c.poll_period.count() <= 0) bad("poll_period must be positive");
    if (c.response_timeout.count() <= 0) bad("response_timeout must be positive");
    if (c.heartbeat_period.count() <= 0) bad("heartbeat_period must be positive");
    if (c.robot_heartbeat_timeout <= c.poll_period)
        bad("robot_heartbeat_timeout must be longer than poll_period");
    if (c.stable_reads < 1) bad("stable_reads must be at least 1");
    if (c.reconnect_backoff_min.count() <= 0 || c.reconnect_backoff_max < c.reconnect_backoff_min)
        bad("reconnect back-off must satisfy 0 < min <= max");
    if (auto p = map_problem(c.map)) bad("map." + p->signal + ": " + p->problem);
}

}  // namespace fibrecell::drivers::abb
