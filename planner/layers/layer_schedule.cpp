#include "planner/layers/layer_schedule.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace fibrecell::planner {

namespace {

constexpr double kMaxLayers = 100000;

void require_positive(double value, const char* name) {
    if (!std::isfinite(value) || value <= 0)
        throw std::invalid_argument(std::string("layer schedule: ") + name +
                                    " must be a positive number, got " + std::to_string(value));
}

}  // namespace

std::vector<ScheduledLayer> layer_schedule(double part_height_mm, const LayerScheduleSpec& spec) {
    const double H = part_height_mm;
    require_positive(H, "part height");
    require_positive(spec.pla_layer_height_mm, "pla_layer_height_mm");
    const double pla_count_real = std::round(H / spec.pla_layer_height_mm);
    if (pla_count_real > kMaxLayers)
        throw std::invalid_argument("layer schedule: part height " + std::to_string(H) +
                                    " mm gives more than 100000 PLA layers");
    const int pla_count = std::max(1, static_cast<int>(pla_count_real));

    // The stack in print order, in printed heights.
    std::vector<ScheduledLayer> layers;
    double top = 0;
    for (int n = 1; n <= pla_count; ++n) {
        top += spec.pla_layer_height_mm;
        layers.push_back(
            {static_cast<int>(layers.size()), Head::pla, spec.pla_layer_height_mm, top, n, 0.0});
        if (spec.has_ccf_after(n)) {
            require_positive(spec.ccf_layer_height_mm, "ccf_layer_height_mm");
            top += spec.ccf_layer_height_mm;
            layers.push_back({static_cast<int>(layers.size()), Head::ccf, spec.ccf_layer_height_mm,
                              top, n, 0.0});
        }
    }

    // Printed stack -> model heights.
    const double scale = H / top;
    const double margin = 1e-3 * spec.pla_layer_height_mm * scale;
    for (ScheduledLayer& layer : layers) {
        const double bottom = layer.z - layer.thickness;
        if (layer.head == Head::pla) {
            layer.slice_z = (bottom + 0.5 * layer.thickness) * scale;
        } else {
            layer.slice_z = std::clamp(bottom * scale, margin, H - margin);
        }
    }
    return layers;
}

}  // namespace fibrecell::planner
