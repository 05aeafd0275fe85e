#include "planner/plan/parameter_sweep.hpp"

#include "planner/stopwatch.hpp"

#include <cmath>
#include <cstdlib>
#include <functional>
#include <stdexcept>

namespace fibrecell::planner {
namespace {

// Each parameter with its job-file range and where it goes.
struct Sweepable {
    std::string name;
    SettingRange range;
    double PlannerSpec::*field;
};

const std::vector<Sweepable>& table() {
    static const std::vector<Sweepable> t = {
        {"p", p_range, &PlannerSpec::p},
        {"sigma_cap_percentile", sigma_cap_percentile_range, &PlannerSpec::sigma_cap_percentile},
        {"crowded_fraction", crowded_fraction_range, &PlannerSpec::crowded_fraction},
    };
    return t;
}

const Sweepable* find(std::string_view name) {
    for (const Sweepable& s : table())
        if (s.name == name) return &s;
    return nullptr;
}

std::string known_names() {
    std::string out;
    for (const Sweepable& s : table()) out += (out.empty() ? "" : ", ") + s.name;
    return out;
}

double parse_value(const Sweepable& s, std::string_view text) {
    const std::string t(text);
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || end != t.c_str() + t.size() || !std::isfinite(v))
        throw std::invalid_argument("sweep: '" + t + "' is not a number");
    const SettingRange& r = s.range;
    const bool low = r.min_exclusive ? v <= r.min : v < r.min;
    if (low || v > r.max)
        throw std::invalid_argument("sweep: " + s.name + " = " + t + " is outside " +
                                    (r.min_exclusive ? "(" : "[") + std::to_string(r.min) + ", " +
                                    std::to_string(r.max) + "]");
    return v;
}

}  // namespace

ParameterSweep parse_sweep(std::string_view text) {
    const auto eq = text.find('=');
    if (eq == std::string_view::npos)
        throw std::invalid_argument(
            "sweep: expected NAME=V1,V2,... (for example p=0,0.5,1,2), not '" + std::string(text) +
            "'");
    ParameterSweep sweep;
    sweep.parameter = std::string(text.substr(0, eq));
    const Sweepable* s = find(sweep.parameter);
    if (!s)
        throw std::invalid_argument("sweep: unknown parameter '" + sweep.parameter + "' (one of " +
                                    known_names() + ")");
    std::string_view rest = text.substr(eq + 1);
    while (true) {
        const auto comma = rest.find(',');
        sweep.values.push_back(parse_value(*s, rest.substr(0, comma)));
        if (comma == std::string_view::npos) break;
        rest = rest.substr(comma + 1);
    }
    if (sweep.values.size() > 16)
        throw std::invalid_argument("sweep: at most 16 values, not " +
                                    std::to_string(sweep.values.size()));
    return sweep;
}

void run_sweep(ParameterSweep& sweep, const JobSpec& job, const FieldStageResult& field,
               LayerStageOptions options, const StepControl& control) {
    const Sweepable* s = find(sweep.parameter);
    if (!s) throw std::invalid_argument("sweep: unknown parameter '" + sweep.parameter + "'");
    sweep.points.clear();
    const double k = static_cast<double>(sweep.values.size());
    for (std::size_t i = 0; i < sweep.values.size(); ++i) {
        JobSpec varied = job;
        varied.planner.*(s->field) = sweep.values[i];
        // The layer stage's own progress ("layers"; slicing reports too, and is quick), folded
        // into this value's share of the sweep.
        const StepControl inner{[&](std::string_view stage, double f) {
                                    if (stage == "layers")
                                        control.report("sweep", (static_cast<double>(i) + f) / k);
                                },
                                control.cancel};
        Stopwatch clock;
        const LayerStageResult r = run_layer_stage(varied, field, options, inner);
        const LayerStageStats& st = r.stats;
        sweep.points.push_back({.value = sweep.values[i],
                                .fibre_length_mm = st.fibre_length_mm,
                                .fibre_paths = st.fibre_paths,
                                .alignment = st.quality.alignment(),
                                .density_correlation = st.quality.density_correlation(),
                                .turning_deg_per_m = st.quality.turning_deg_per_m(),
                                .min_spacing_mm = st.fibre_min_spacing_mm,
                                .seconds = clock.elapsed()});
        control.check_cancel();
    }
    control.report("sweep", 1.0);
}

}  // namespace fibrecell::planner
