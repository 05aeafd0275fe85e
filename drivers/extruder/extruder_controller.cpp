#include "drivers/extruder/extruder_controller.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <numbers>
#include <stdexcept>

namespace fibrecell::drivers {
namespace {

// Fixed-point text for a G-code parameter: num(12.5, 1) -> "12.5".
std::string num(double v, int decimals) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(decimals) << v;
    return s.str();
}

void require_positive(double v, const char* what) {
    if (!(v > 0) || !std::isfinite(v))
        throw std::invalid_argument(std::string("extruder: ") + what + " must be positive, got " +
                                    std::to_string(v));
}

}  // namespace

ExtruderController::ExtruderController(ExtruderConfig config) : config_(std::move(config)) {}

std::vector<std::string> ExtruderController::prepare(const HotendTargets& targets, bool wait) {
    std::vector<std::string> out{"M83"};
    const auto tool_temp = [](int t, double c, bool w) {
        std::string l = w ? "M109 T" : "M104 T";
        l += std::to_string(t);
        l += " S";
        l += num(c, 0);
        return l;
    };
    out.push_back(tool_temp(config_.pla_tool, targets.pla_c, false));
    out.push_back(tool_temp(config_.ccf_tool, targets.ccf_c, false));
    if (wait) {
        out.push_back(tool_temp(config_.pla_tool, targets.pla_c, true));
        out.push_back(tool_temp(config_.ccf_tool, targets.ccf_c, true));
    }
    return out;
}

std::vector<std::string> ExtruderController::select(Head head) {
    const int t = head == Head::pla ? config_.pla_tool : config_.ccf_tool;
    if (t == tool_) return {};
    tool_ = t;
    std::string l = "T";
    l += std::to_string(t);
    return {l};
}

std::vector<std::string> ExtruderController::extrude(double e_mm, double feed_mm_s, const char* what) {
    if (feed_mm_s > config_.max_feed_mm_s)
        throw std::invalid_argument(std::string("extruder: ") + what + " feed " +
                                    std::to_string(feed_mm_s) + " mm/s exceeds max_feed_mm_s " +
                                    std::to_string(config_.max_feed_mm_s));
    std::vector<std::string> out;
    const int n = static_cast<int>(std::ceil(std::abs(e_mm) / config_.max_extrusion_length_mm));
    // Segment ends rounded on the cumulative length, so the pieces add up to exactly e_mm.
    const auto rounded = [](double v) { return std::round(v * 1e5) / 1e5; };
    for (int i = 0; i < n; ++i) {
        const double piece = rounded(e_mm * (i + 1) / n) - rounded(e_mm * i / n);
        std::string l = "G1 E";
        l += num(piece, 5);
        l += " F";
        l += num(feed_mm_s * 60.0, 1);
        out.push_back(std::move(l));
    }
    return out;
}

std::vector<std::string> ExtruderController::extrude_pla(double path_mm, double tcp_speed_mm_s,
                                                         double line_width_mm,
                                                         double layer_height_mm) {
    require_positive(path_mm, "PLA path length");
    require_positive(tcp_speed_mm_s, "TCP speed");
    require_positive(line_width_mm, "line width");
    require_positive(layer_height_mm, "layer height");
    const double d = config_.filament_diameter_mm;
    const double ratio = line_width_mm * layer_height_mm / (std::numbers::pi * d * d / 4.0);
    auto out = select(Head::pla);
    for (auto& l : extrude(path_mm * ratio, tcp_speed_mm_s * ratio, "PLA")) out.push_back(std::move(l));
    return out;
}

std::vector<std::string> ExtruderController::thread_fibre() {
    auto out = select(Head::ccf);
    for (auto& l : extrude(config_.cutter_distance_mm, config_.thread_speed_mm_s, "thread feed"))
        out.push_back(std::move(l));
    return out;
}

std::vector<std::string> ExtruderController::feed_fibre(double path_mm, double tcp_speed_mm_s) {
    require_positive(path_mm, "fibre path length");
    require_positive(tcp_speed_mm_s, "TCP speed");
    auto out = select(Head::ccf);
    for (auto& l : extrude(path_mm, tcp_speed_mm_s, "fibre")) out.push_back(std::move(l));
    return out;
}

std::vector<std::string> ExtruderController::cut() {
    const CutterConfig& c = config_.cutter;
    const std::string hold = "G4 P" + std::to_string(c.hold_ms);
    switch (c.method) {
        case CutMethod::spindle: return {"M3 S255", hold, "M5"};
        case CutMethod::servo: {
            const std::string p = "M280 P" + std::to_string(c.servo_index);
            return {"M400", p + " S" + num(c.cut_angle_deg, 0), hold, p + " S" + num(c.open_angle_deg, 0)};
        }
        case CutMethod::pin: break;
    }
    const std::string p = "M42 P" + std::to_string(c.pin);
    return {"M400", p + " S255", hold, p + " S0"};
}

std::vector<std::string> ExtruderController::retract() {
    auto out = select(Head::pla);
    for (auto& l : extrude(-config_.retract_mm, config_.retract_speed_mm_s, "retract")) out.push_back(std::move(l));
    return out;
}

std::vector<std::string> ExtruderController::prime() {
    auto out = select(Head::pla);
    for (auto& l : extrude(config_.retract_mm, config_.retract_speed_mm_s, "prime")) out.push_back(std::move(l));
    return out;
}

}  // namespace fibrecell::drivers
