#include "daemon/printer/print_figures.hpp"

#include <algorithm>
#include <cstdio>
#include <optional>

namespace fibrecell::daemon::printer {

namespace abb = drivers::abb;
using nlohmann::json;

namespace {

json summary_json(const sync::LatencySummary& s) {
    return {{"count", s.count}, {"median", s.median}, {"p99", s.p99}, {"max", s.max}};
}

// The engine's timing of one event kind, when it has seen one.
std::optional<sync::KindTiming> timing_of(const sync::SyncStatus& s, abb::EventKind kind) {
    for (const auto& t : s.stats.timing)
        if (t.kind == kind) return t;
    return std::nullopt;
}

json shortfall_json(const sync::Shortfall& f) {
    return {{"kind", sync::to_string(f.kind)},
            {"event", f.sequence},
            {"layer", f.layer + 1},
            {"path", f.path + 1},
            {"mm", f.mm}};
}

std::string describe(const sync::Shortfall& f) {
    char mm[32];
    std::snprintf(mm, sizeof mm, "%.1f mm", f.mm);
    const std::string where = " at event " + std::to_string(f.sequence) + " (layer " +
                              std::to_string(f.layer + 1) + ", path " + std::to_string(f.path + 1) +
                              ")";
    switch (f.kind) {
        case sync::ShortfallKind::fibre_feed_dropped:
            return "fibre path" + where + ": " + mm + " not fed";
        case sync::ShortfallKind::pla_feed_dropped:
            return "PLA path" + where + ": " + mm + " not extruded";
        case sync::ShortfallKind::late_cut:
            return "cut" + where + ": " + mm + " late";
    }
    return "?";
}

}  // namespace

json live_sync_json(const sync::SyncStatus& s) {
    json out = {{"last_confirmed", s.last_confirmed}, {"faulted", s.faulted}, {"paused", s.paused}};
    if (const auto cut = timing_of(s, abb::EventKind::cut))
        out["cut_error_mm"] = summary_json(cut->position_error_mm);
    sync::LatencySummary latency;
    for (const auto& t : s.stats.timing)
        if (t.submit_ms.count > latency.count) latency = t.submit_ms;
    if (latency.count > 0) out["latency_ms"] = summary_json(latency);
    return out;
}

json result_sync_json(const sync::SyncStatus& s) {
    json out = json::object();
    if (const auto cut = timing_of(s, abb::EventKind::cut))
        out["cut_error_mm"] = summary_json(cut->position_error_mm);
    // Event -> first board command, per kind (the engine's own measurement).
    json latency = json::object();
    for (const auto& t : s.stats.timing)
        latency[std::string(abb::to_string(t.kind))] = summary_json(t.submit_ms);
    out["latency_ms"] = latency;
    // What fell short of the plan, path by path (a completed print with any is
    // completed_with_warnings).
    json shortfalls = json::array();
    for (const auto& f : s.stats.shortfalls) shortfalls.push_back(shortfall_json(f));
    out["shortfalls"] = shortfalls;
    return out;
}

std::string shortfall_reason(const std::vector<sync::Shortfall>& all) {
    constexpr std::size_t shown = 3;
    std::string r = std::to_string(all.size()) + (all.size() == 1 ? " shortfall from the plan: "
                                                                  : " shortfalls from the plan: ");
    for (std::size_t i = 0; i < std::min(all.size(), shown); ++i)
        r += (i ? "; " : "") + describe(all[i]);
    if (all.size() > shown) r += "; and " + std::to_string(all.size() - shown) + " more";
    return r + " (result.json: shortfalls)";
}

}  // namespace fibrecell::daemon::printer
