#pragma once
// Turns print events into Marlin commands for the dual head: E0 extrudes PLA, E1 feeds the
// continuous fibre, a pin or servo drives the cutter (docs/marlin-link.md). It remembers the
// selected tool so that tool changes are only emitted when needed; everything else is a pure
// function of the configuration. E moves are relative (M83).

#include "drivers/extruder/extruder_config.hpp"

#include <string>
#include <vector>

namespace fibrecell::drivers {

enum class Head { pla, ccf };

// The print's hotend temperatures (the job's process.*.nozzle_temp_c) [degC].
struct HotendTargets {
    double pla_c = 200;
    double ccf_c = 250;

    double of(Head h) const { return h == Head::pla ? pla_c : ccf_c; }
};

class ExtruderController {
  public:
    explicit ExtruderController(ExtruderConfig config);

    // Relative E, both hotends to `targets`; with `wait`, M109 for each before returning.
    std::vector<std::string> prepare(const HotendTargets& targets, bool wait);
    // T<n> when the head changes.
    std::vector<std::string> select(Head head);
    // PLA along `path_mm` of line at the robot's TCP speed [mm/s]: E = path * w * h / filament
    // area, at the matching feed rate; split under max_extrusion_length_mm.
    std::vector<std::string> extrude_pla(double path_mm, double tcp_speed_mm_s, double line_width_mm,
                                         double layer_height_mm);
    // At a fibre path start: push the fibre the cutter distance to thread the nozzle.
    std::vector<std::string> thread_fibre();
    // Fibre fed at the TCP speed for `path_mm` of path.
    std::vector<std::string> feed_fibre(double path_mm, double tcp_speed_mm_s);
    // The cut with the feed stopped: M400 (the planner has drained), then the cutter. With
    // SPINDLE_FEATURE, M3/M5 synchronise in the firmware.
    std::vector<std::string> cut();
    std::vector<std::string> retract();
    std::vector<std::string> prime();

    // The board restarted (a reset, a replug): it is on its default tool again, so the next
    // select() sends T<n> whatever was selected before.
    void forget_tool() { tool_ = -1; }

    const ExtruderConfig& config() const { return config_; }

  private:
    std::vector<std::string> extrude(double e_mm, double feed_mm_s, const char* what);
    ExtruderConfig config_;
    int tool_ = -1;  // unknown until the first select
};

}  // namespace fibrecell::drivers
