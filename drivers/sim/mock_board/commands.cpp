// The commands as the firmware runs them: the planner's blocks in (scaled) real time, the
// heaters' first-order model, blocking waits with their busy and temperature lines, pin events.

#include "drivers/sim/mock_board/board_state.hpp"

#include "drivers/marlin/marlin_line.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace fibrecell::drivers::sim {

// ---- Time: planner and heaters --------------------------------------------------------

void MockGt2560::Impl::advance(double t) {
    while (!planner.empty() && planner.front().end_s <= t) planner.pop_front();
    const double dt = t - thermal_t;
    thermal_t = t;
    for (int i = 0; i < 3; ++i) {
        Heater& h = heaters[static_cast<std::size_t>(i)];
        const double goal = h.target_c > 0 ? h.target_c : o.ambient_c;
        const double tau = i == 2 ? o.bed_tau_s : o.hotend_tau_s;
        h.temp_c += (goal - h.temp_c) * (1.0 - std::exp(-dt / tau));
    }
}

std::string MockGt2560::Impl::temperature_line() const {
    char buf[200];
    const Heater& a = heaters[static_cast<std::size_t>(tool)];
    std::snprintf(buf, sizeof buf,
                  "T:%.2f /%.2f B:%.2f /%.2f T0:%.2f /%.2f T1:%.2f /%.2f @:0 B@:0 @0:0 @1:0",
                  a.temp_c, a.target_c, heaters[2].temp_c, heaters[2].target_c, heaters[0].temp_c,
                  heaters[0].target_c, heaters[1].temp_c, heaters[1].target_c);
    return buf;
}

// ---- Executing commands ---------------------------------------------------------------

void MockGt2560::Impl::finish(Exec& e, double t) {
    executed.push_back(
        {t, e.line, e.text, e.move_start_s, e.move_end_s, executed_dropped + executed.size()});
    if (o.max_log > 0 && executed.size() > o.max_log) {
        executed.pop_front();
        ++executed_dropped;
    }
    cv.notify_all();
    if (e.line && delay.count(*e.line)) {
        e.wait = Wait::ok_delay;
        e.until_s = t + delay[*e.line];
        delay.erase(*e.line);
        return;
    }
    send_ok(e);
}

void MockGt2560::Impl::send_ok(Exec& e) {
    e.wait = Wait::none;
    if (!e.ok_pending) return;
    e.ok_pending = false;
    if (e.line && swallow.erase(*e.line)) return;
    if (o.advanced_ok) {
        emit("ok" + (e.line ? " N" + std::to_string(*e.line) : std::string()) + " P" +
             std::to_string(o.planner_blocks - static_cast<int>(planner.size())) + " B" +
             std::to_string(o.command_buffer_lines - static_cast<int>(queue.size())));
    } else {
        emit("ok");
    }
}

void MockGt2560::Impl::pin_event(const std::string& text, double t) {
    pins.push_back({t, text, static_cast<int>(planner.size()), last_move_end});
    if (o.max_log > 0 && pins.size() > o.max_log) pins.pop_front();
}

void MockGt2560::Impl::begin(Exec& e, double t) {
    const std::string& w = e.word;
    const std::string& c = e.text;
    e.started_s = e.last_busy_s = e.last_report_s = t;
    if (w == "G0" || w == "G1") {
        e.wait = Wait::planner_slot;
    } else if (w == "M400" || w == "M3" || w == "M4" || w == "M5") {
        e.wait = Wait::planner_empty;
    } else if (w == "G4") {
        e.wait = Wait::planner_empty;
        e.dwell_s = param(c, 'S').value_or(param(c, 'P').value_or(0) / 1000.0);
    } else if (w == "M104" || w == "M109" || w == "M140" || w == "M190") {
        const bool bed = w == "M140" || w == "M190";
        const int h = bed ? 2 : static_cast<int>(param(c, 'T').value_or(tool));
        if (h < 0 || h > 2) {
            emit("echo:Invalid extruder " + std::to_string(h));
            return finish(e, t);
        }
        const auto s = param(c, 'S');
        const auto r = param(c, 'R');
        Heater& heater = heaters[static_cast<std::size_t>(h)];
        heater.target_c = s.value_or(r.value_or(0));
        const bool wait = w == "M109" || w == "M190";
        // S waits only when heating, R also when cooling (M109.md).
        if (wait && (r || heater.temp_c < heater.target_c - o.temp_window_c)) {
            e.wait = Wait::heating;
            e.heater = h;
            e.wait_cooling = r.has_value();
            heat_wait_broken = false;
            return;
        }
        finish(e, t);
    } else if (w == "M105") {
        emit("ok " + temperature_line());
        e.ok_pending = false;
        finish(e, t);
    } else if (w == "M155") {
        autoreport_s = param(c, 'S').value_or(0);
        last_autoreport = t;
        finish(e, t);
    } else if (w == "M113") {
        keepalive_s = param(c, 'S').value_or(keepalive_s);
        finish(e, t);
    } else if (w == "M115") {
        emit(
            "FIRMWARE_NAME:Marlin 1.1.9 (Github) SOURCE_CODE_URL:https://github.com/"
            "MarlinFirmware/Marlin PROTOCOL_VERSION:1.0 MACHINE_TYPE:3D Printer "
            "EXTRUDER_COUNT:2 UUID:cede2a2f-41a2-4748-9b12-c55c62f367ff");
        for (const char* cap :
             {"SERIAL_XON_XOFF:0", "EEPROM:1", "VOLUMETRIC:1", "AUTOREPORT_TEMP:1", "PROGRESS:0",
              "PRINT_JOB:1", "AUTOLEVEL:0", "Z_PROBE:0", "LEVELING_DATA:0", "BUILD_PERCENT:0",
              "SOFTWARE_POWER:0", "TOGGLE_LIGHTS:0", "CASE_LIGHT_BRIGHTNESS:0"})
            emit(std::string("Cap:") + cap);
        emit(std::string("Cap:EMERGENCY_PARSER:") + (o.emergency_parser ? "1" : "0"));
        emit("Cap:AUTOREPORT_SD_STATUS:0");
        emit("Cap:THERMAL_PROTECTION:1");
        finish(e, t);
    } else if (w == "M114") {
        char buf[100];
        std::snprintf(buf, sizeof buf, "X:0.00 Y:0.00 Z:0.00 E:%.2f Count X:0 Y:0 Z:0",
                      e_pos[static_cast<std::size_t>(tool)]);
        emit(buf);
        finish(e, t);
    } else if (w == "M42" || w == "M280") {
        pin_event(c, t);  // no planner sync: acts when dequeued (M42.cpp, M280.cpp)
        finish(e, t);
    } else if (w == "T0" || w == "T1") {
        tool = w == "T1" ? 1 : 0;
        emit("echo:Home XYZ first");  // the GT2560 here has no axes to home
        emit("echo:Active Extruder: " + std::to_string(tool));
        finish(e, t);
    } else if (w == "M302") {
        // M302 P1 allows cold extrusion, P0 forbids it; S sets the minimum temperature.
        if (auto v = param(c, 'S')) min_extrude_c = *v;
        if (auto v = param(c, 'P')) cold_extrusion_allowed = *v != 0;
        finish(e, t);
    } else if (w == "M82" || w == "M83") {
        relative_e = w == "M83";
        finish(e, t);
    } else if (w == "G92") {
        if (auto v = param(c, 'E')) e_pos[static_cast<std::size_t>(tool)] = *v;
        finish(e, t);
    } else if (w == "M110") {
        if (!e.line) {
            if (auto j = param(c, 'N')) last_n = static_cast<std::int64_t>(*j);
        }
        finish(e, t);
    } else if (w == "M108" || w == "M112" || w == "M410" || w == "M999" || w == "G28" ||
               w == "G90" || w == "G91" || w == "M17" || w == "M18" || w == "M84" || w == "M117" ||
               w == "M106" || w == "M107") {
        finish(e, t);
    } else {
        emit("echo:Unknown command: \"" + c + "\"");
        finish(e, t);
    }
}

void MockGt2560::Impl::queue_move(Exec& e, double t) {
    const double f = param(e.text, 'F').value_or(feed_mm_min);
    feed_mm_min = f;
    double de = 0;
    if (auto v = param(e.text, 'E')) {
        double& pos = e_pos[static_cast<std::size_t>(tool)];
        de = relative_e ? *v : *v - pos;
        pos = relative_e ? pos + *v : *v;
    }
    // PREVENT_COLD_EXTRUSION: the E part of a move is dropped, once per move, with a message.
    if (de != 0 && !cold_extrusion_allowed &&
        heaters[static_cast<std::size_t>(tool)].temp_c < min_extrude_c) {
        emit("echo: cold extrusion prevented");
        de = 0;
        ++cold_refusals;
    }
    const double duration = f > 0 ? std::abs(de) / (f / 60.0) : 0;
    const double start = std::max(t, planner.empty() ? t : planner.back().end_s);
    planner.push_back({start + duration});
    last_move_end = start + duration;
    e.move_start_s = start;
    e.move_end_s = start + duration;
}

// Returns true when the current command is complete and its ok is out.
bool MockGt2560::Impl::progress(Exec& e, double t) {
    switch (e.wait) {
        case Wait::none:
            return true;
        case Wait::planner_slot:
            if (static_cast<int>(planner.size()) >= o.planner_blocks) break;
            queue_move(e, t);
            finish(e, t);
            return e.wait == Wait::none;
        case Wait::planner_empty:
            if (!planner.empty()) break;
            if (e.word == "G4") {
                e.wait = Wait::dwell;
                e.until_s = t + e.dwell_s;
                return progress(e, t);
            }
            if (e.word != "M400") pin_event(e.text, t);  // M3/M5 act after the sync
            finish(e, t);
            return e.wait == Wait::none;
        case Wait::dwell:
            if (t < e.until_s) break;
            finish(e, t);
            return e.wait == Wait::none;
        case Wait::heating: {
            const Heater& h = heaters[static_cast<std::size_t>(e.heater)];
            if (heat_wait_broken) {
                heat_wait_broken = false;
                finish(e, t);
                return e.wait == Wait::none;
            }
            const bool in_window = std::abs(h.temp_c - h.target_c) <= o.temp_window_c;
            if (in_window && e.in_window_since < 0) e.in_window_since = t;
            if (!in_window) e.in_window_since = -1;
            if (e.in_window_since >= 0 && t - e.in_window_since >= o.residency_s) {
                finish(e, t);
                return e.wait == Wait::none;
            }
            if (t - e.last_report_s >= 1.0) {  // heat-up progress every second
                e.last_report_s = t;
                const std::string w = e.in_window_since < 0
                                          ? " W:?"
                                          : " W:" + std::to_string(static_cast<int>(
                                                        o.residency_s - (t - e.in_window_since)));
                emit(temperature_line() + w);
            }
            break;
        }
        case Wait::ok_delay:
            if (t < e.until_s) return false;
            send_ok(e);
            return true;
    }
    if (e.wait != Wait::ok_delay && t - e.last_busy_s >= keepalive_s) {
        e.last_busy_s = t;
        emit("echo:busy: processing");
    }
    return false;
}

void MockGt2560::Impl::step(double t) {
    if (booting) {
        if (t < boot_until) return;
        booting = false;
        rx.clear();  // input during the bootloader window is lost
        banner();
    }
    if (killed) return;
    advance(t);
    for (const auto& a : actions) emit("//action:" + a);
    actions.clear();
    if (runaway) {
        const int h = *runaway;
        runaway.reset();
        return kill("Thermal Runaway, system stopped! Heater_ID: " +
                    std::string(h == 2 ? "bed" : std::to_string(h)));
    }
    if (autoreport_s > 0 && t - last_autoreport >= autoreport_s) {
        last_autoreport = t;
        emit(" " + temperature_line());
    }
    for (int guard = 0; guard < 64 && !killed && !booting; ++guard) {
        if (current) {
            if (!progress(*current, t)) return;
            current.reset();
        }
        get_serial_commands();
        if (queue.empty()) return;
        Exec e;
        e.text = queue.front().first;
        e.line = queue.front().second;
        e.word = marlin::command_word(e.text);
        queue.pop_front();
        current = std::move(e);
        begin(*current, t);
    }
}

}  // namespace fibrecell::drivers::sim
