#include "drivers/extruder/extruder_config.hpp"

namespace fibrecell::drivers {
namespace {

// Cell files from before the job's temperatures took effect.
void moved_temperature(config::Section& head) {
    if (head.has("temp_c"))
        head.fail("temp_c",
                  "the print temperature is the job's (process.pla/ccf.nozzle_temp_c); the cell "
                  "limits it with max_temp_c");
}

}  // namespace

ExtruderConfig load_extruder_config(config::Section s) {
    ExtruderConfig c;
    {
        config::Section l = s.section("link");
        auto& lc = c.link;
        lc.serial.device = l.get_or<std::string>("port", "/dev/ttyUSB0");
        lc.serial.baud_rate = l.integer("baud_rate", 250000, 2400, 2000000);
        lc.serial.hangup_on_close = l.get_or<bool>("hangup_on_close", false);
        lc.boot_timeout = marlin::Seconds(l.number("boot_timeout_s", 3.0, 0, 60));
        lc.handshake_timeout = marlin::Seconds(l.number("handshake_timeout_s", 5.0, 0.1, 60));
        lc.autoreport_interval_s = l.integer("autoreport_interval_s", 1, 0, 60);
        auto& p = lc.protocol;
        p.window_lines = l.integer("window_lines", 1, 1, 3);  // BUFSIZE 4 - 1
        p.window_bytes = l.integer("window_bytes", 100, 32, 120);  // under the 128-byte RX ring
        p.ok_timeout = marlin::Seconds(l.number("ok_timeout_s", 5.0, 0.05, 600, true));
        p.motion_timeout = marlin::Seconds(l.number("motion_timeout_s", 30.0, 0.05, 3600, true));
        p.long_timeout = marlin::Seconds(l.number("long_timeout_s", 300.0, 0.05, 36000, true));
        p.heating_liveness = marlin::Seconds(l.number("heating_liveness_s", 10.0, 0.05, 600, true));
        p.silence_timeout = marlin::Seconds(l.number("silence_timeout_s", 30.0, 0.05, 3600, true));
        p.keepalive_liveness =
            marlin::Seconds(l.number("keepalive_liveness_s", 6.0, 0.05, 3600, true));
        p.max_probes = l.integer("max_probes", 3, 1, 20);
        p.max_consecutive_resends = l.integer("max_consecutive_resends", 10, 1, 100);
        const std::string ro = l.choice("resend_ok", "detect", {"detect", "always", "never"});
        p.resend_ok = ro == "always"  ? marlin::ResendOk::always
                      : ro == "never" ? marlin::ResendOk::never
                                      : marlin::ResendOk::detect;
        l.finish();
    }
    {
        config::Section p = s.section("pla");
        c.pla_tool = p.integer("tool", 0, 0, 1);
        moved_temperature(p);
        c.pla_nozzle_diameter_mm = p.number("nozzle_diameter_mm", 0.8, 0.05, 5);
        c.pla_max_temp_c = p.number("max_temp_c", 260, 0, 450);
        c.filament_diameter_mm = p.number("filament_diameter_mm", 1.75, 0.5, 3.5);
        c.retract_mm = p.number("retract_mm", 1.0, 0, 20);
        c.retract_speed_mm_s = p.number("retract_speed_mm_s", 40, 0, 150, true);
        p.finish();
    }
    {
        config::Section f = s.section("ccf");
        c.ccf_tool = f.integer("tool", 1, 0, 1);
        moved_temperature(f);
        c.ccf_nozzle_diameter_mm = f.number("nozzle_diameter_mm", 1.0, 0.05, 5);
        c.ccf_max_temp_c = f.number("max_temp_c", 260, 0, 450);
        c.cutter_distance_mm = f.number("cutter_distance_mm", c.cutter_distance_mm, 0, 500);
        c.thread_speed_mm_s = f.number("thread_speed_mm_s", 5, 0, 100, true);
        f.finish();
    }
    if (c.pla_tool == c.ccf_tool) s.fail("ccf.tool", "must differ from pla.tool");
    {
        config::Section k = s.section("cutter");
        const std::string m = k.choice("method", "pin", {"pin", "servo", "spindle"});
        c.cutter.method = m == "servo" ? CutMethod::servo : m == "spindle" ? CutMethod::spindle : CutMethod::pin;
        c.cutter.pin = k.integer("pin", 11, 0, 69);  // ATmega2560 digital pins
        c.cutter.servo_index = k.integer("servo_index", 0, 0, 3);
        c.cutter.cut_angle_deg = k.number("cut_angle_deg", 90, 0, 180);
        c.cutter.open_angle_deg = k.number("open_angle_deg", 0, 0, 180);
        c.cutter.hold_ms = k.integer("hold_ms", 200, 0, 10000);
        k.finish();
    }
    c.min_extrude_temp_c = s.number("min_extrude_temp_c", 170, 0, 450);
    c.max_extrusion_length_mm = s.number("max_extrusion_length_mm", 200, 1, 10000, true);
    c.max_feed_mm_s = s.number("max_feed_mm_s", 50, 0, 500, true);
    s.finish();
    return c;
}

}  // namespace fibrecell::drivers
