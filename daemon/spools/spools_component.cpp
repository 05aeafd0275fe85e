#include "daemon/spools/spools_component.hpp"

#include "config/utc_time.hpp"
#include "daemon/api/api_error.hpp"
#include "daemon/api/params.hpp"
#include "daemon/jobs/job_journal.hpp"
#include "daemon/jobs/planned_use.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fibrecell::daemon::spools {

using api::ApiError;
using api::CallContext;
using jobs::JobRecord;
using nlohmann::json;

namespace {

std::string metres(double mm) { return fmt::format("{:.2f} m", mm / 1000.0); }

std::string tool_param(api::ParamReader& p) {
    const std::string tool = p.string("tool");
    if (tool != "T0" && tool != "T1") p.fail("tool", "'" + tool + "' is not a hotend: T0 (PLA) or T1 (fibre)");
    return tool;
}

// What the job has fed already over its runs (its journal's last `used`), zero when none.
jobs::JournalUsed fed_already(const std::filesystem::path& job_dir) {
    try {
        const auto journal = job_dir / "journal.jsonl";
        if (std::filesystem::exists(journal))
            return jobs::read_journal(journal).used.value_or(jobs::JournalUsed{});
    } catch (const std::exception&) {
    }
    return {};
}

}  // namespace

SpoolsComponent::SpoolsComponent(jobs::JobsComponent& jobs, printer::PrinterComponent& printer,
                                 queue::QueueComponent& queue, devices::CellComponent& cell,
                                 const CellConfig& cell_config, SpoolsConfig config)
    : jobs_(jobs), queue_(queue), config_(config),
      pla_tool_("T" + std::to_string(cell_config.extruder.pla_tool)),
      fibre_tool_("T" + std::to_string(cell_config.extruder.ccf_tool)),
      file_(std::filesystem::path(cell_config.state_dir) / "spools.json") {
    printer.add_start_gate([this](const JobRecord& r) { return short_of(r, "start"); });
    queue.add_admission_check([this](const JobRecord& r) { return short_of(r, "be queued"); });
    printer.on_feed([this](const printer::PrintRunner::Feed& f) { fed_and_saved(f); });
    printer.on_print_finished([this](std::int64_t) {
        const json needs = queue_needs();
        std::lock_guard lock(mu_);
        if (unsaved_) save();
        publish(needs);
    });
    cell.add_status_part([this](json& status) {
        std::lock_guard lock(mu_);
        json s = json::object();
        for (const auto& [tool, sp] : state_.spools) s[tool] = {{"material", sp.material},
                                                                {"remaining_m", sp.remaining_mm() / 1000.0}};
        status["spools"] = s;
    });
}

void SpoolsComponent::register_endpoints(component::Endpoints& endpoints) {
    endpoints.method("spool.list", [this](const json& params, const CallContext& ctx) {
        api::ParamReader(ctx.method, params).finish();
        const json needs = queue_needs();
        std::lock_guard lock(mu_);
        return view(needs);
    });
    endpoints.method("spool.load", [this](const json& params, const CallContext& ctx) {
        api::ParamReader p(ctx.method, params);
        const std::string tool = tool_param(p);
        Spool s;
        s.material = p.string("material");
        if (s.material.empty()) p.fail("material", "must not be empty (\"PLA\", \"CF 1K\")");
        s.tow = p.string_opt("tow").value_or("");
        s.lot = p.string_opt("lot").value_or("");
        constexpr double most = 1e9;  // mm: a thousand kilometres
        if (p.has("diameter_mm")) s.diameter_mm = p.number_or("diameter_mm", 0, 0.01, 10);
        if (p.has("length_mm") == p.has("mass_g"))
            p.fail("length_mm", "give the spool's length (length_mm) or its mass (mass_g with "
                                "density_g_cm3 and diameter_mm), one of them");
        if (p.has("length_mm")) {
            s.loaded_mm = p.number_or("length_mm", 0, 0, most);
            if (!(s.loaded_mm > 0)) p.fail("length_mm", "must be more than 0");
        } else {
            const double mass = p.number_or("mass_g", 0, 0, 1e7);
            if (!p.has("density_g_cm3")) p.fail("density_g_cm3", "is needed with mass_g");
            const double density = p.number_or("density_g_cm3", 0, 0.1, 20);
            if (!s.diameter_mm) p.fail("diameter_mm", "is needed with mass_g");
            if (!(mass > 0)) p.fail("mass_g", "must be more than 0");
            // g / (g/mm^3 * mm^2) = mm
            const double area = std::numbers::pi * *s.diameter_mm * *s.diameter_mm / 4.0;
            s.loaded_mm = mass / (density / 1000.0 * area);
        }
        p.finish();
        s.loaded_at = config::utc_now();
        const json needs = queue_needs();
        std::lock_guard lock(mu_);
        const SpoolState before = state_;
        state_.spools[tool] = s;
        commit(before);
        spdlog::info("spool.loaded {} {} {} by {}", tool, s.material, metres(s.loaded_mm), ctx.peer);
        publish(needs);
        return view(needs);
    });
    endpoints.method("spool.unload", [this](const json& params, const CallContext& ctx) {
        api::ParamReader p(ctx.method, params);
        const std::string tool = tool_param(p);
        p.finish();
        const json needs = queue_needs();
        std::lock_guard lock(mu_);
        if (!state_.spools.contains(tool))
            throw ApiError::conflict(tool + " has no spool loaded");
        const SpoolState before = state_;
        state_.spools.erase(tool);
        commit(before);
        spdlog::info("spool.unloaded {} by {}", tool, ctx.peer);
        publish(needs);
        return view(needs);
    });
    endpoints.event(api::notify::spools);
    endpoints_ = endpoints;
}

void SpoolsComponent::start() {
    std::lock_guard lock(mu_);
    try {
        state_ = read_spools(file_);
    } catch (const std::exception& e) {
        // Nothing is known of the spools: none is checked until the operator loads them again.
        spdlog::error("spools.unreadable {}: no spool is known; load them again", e.what());
        note_ = std::string("spools.json was unreadable at start-up (") + e.what() +
                "): load the spools again";
        return;
    }
    // The job charged last may have fed more than spools.json (saved per layer) says: its journal
    // (saved every poll) knows, when the service died mid-print.
    const Charged c = state_.charged;
    if (c.job <= 0) return;
    const jobs::JournalUsed journal = fed_already(jobs_.store().job_dir(c.job));
    const double pla = journal.pla_mm - c.pla_mm, fibre = journal.fibre_mm - c.fibre_mm;
    if (pla <= 1e-6 && fibre <= 1e-6) return;
    fed(std::max(0.0, pla), std::max(0.0, fibre));
    state_.charged.pla_mm = std::max(c.pla_mm, journal.pla_mm);
    state_.charged.fibre_mm = std::max(c.fibre_mm, journal.fibre_mm);
    note_ = fmt::format("at start-up job {}'s journal showed {:.1f} mm of fibre and {:.1f} mm of "
                        "PLA fed beyond spools.json (saved every layer): charged now; what the "
                        "board fed after the journal's last record (at most a poll) is not counted",
                        c.job, std::max(0.0, fibre), std::max(0.0, pla));
    spdlog::warn("spools.charged_from_journal {}", note_);
    save();
}

bool SpoolsComponent::join(Deadline) {
    std::lock_guard lock(mu_);
    if (unsaved_) save();
    return true;
}

std::optional<std::string> SpoolsComponent::short_of(const JobRecord& job, const char* doing) const {
    if (config_.check == SpoolCheck::off) return std::nullopt;
    const auto planned = jobs::planned_use(jobs_.store().plan_dir(job.id));
    if (!planned) return std::nullopt;  // still planning: checked when it starts
    const jobs::JournalUsed done = fed_already(jobs_.store().job_dir(job.id));
    const auto needs = [&](double planned_mm, double done_mm) {
        const double left = std::max(0.0, planned_mm - done_mm);
        return left > 0 ? left * (1 + config_.margin_percent / 100.0) + config_.margin_m * 1000.0 : 0.0;
    };
    std::vector<std::string> short_by;
    std::lock_guard lock(mu_);
    for (const auto& [tool, what, planned_mm, done_mm] :
         {std::tuple{fibre_tool_, "fibre", planned->fibre_m * 1000.0, done.fibre_mm},
          std::tuple{pla_tool_, "PLA", planned->pla_m * 1000.0, done.pla_mm}}) {
        const auto it = state_.spools.find(tool);
        if (it == state_.spools.end()) continue;  // no spool known: not checked
        const double need = needs(planned_mm, done_mm);
        if (it->second.remaining_mm() >= need) continue;
        std::string text = fmt::format("{} of {} ({} planned", metres(need), what, metres(planned_mm));
        if (done_mm > 0) text += ", " + metres(done_mm) + " fed already";
        text += fmt::format(", margin {}% + {:.2f} m); {} ({}{}) has {} left", config_.margin_percent,
                            config_.margin_m, tool, it->second.material,
                            it->second.lot.empty() ? "" : ", lot " + it->second.lot,
                            metres(it->second.remaining_mm()));
        short_by.push_back(text);
    }
    if (short_by.empty()) return std::nullopt;
    std::string why = "job " + std::to_string(job.id) + " needs ";
    for (std::size_t i = 0; i < short_by.size(); ++i) why += (i ? "; and " : "") + short_by[i];
    why += ": load a fuller spool (`fibrecell spool load`)";
    if (config_.check == SpoolCheck::warn) {
        spdlog::warn("spools.short job {} may {} (spools.check: warn): {}", job.id, doing, why);
        return std::nullopt;
    }
    return why;
}

void SpoolsComponent::fed(double pla_mm, double fibre_mm) {
    for (const auto& [tool, mm] : {std::pair{pla_tool_, pla_mm}, std::pair{fibre_tool_, fibre_mm}})
        if (auto it = state_.spools.find(tool); it != state_.spools.end()) it->second.used_mm += mm;
    unsaved_ = true;
}

void SpoolsComponent::fed_and_saved(const printer::PrintRunner::Feed& f) {
    {
        std::lock_guard lock(mu_);
        Charged& c = state_.charged;
        if (c.job != f.job) c = {f.job, f.run, 0, 0};
        if (c.run != f.run) {
            // A new run of the job (a re-entry): its count continues from the journal's, which
            // may lag what was charged by the records a crash lost; the spools keep what they
            // charged.
            c.run = f.run;
            c.pla_mm = std::min(c.pla_mm, f.used.pla_mm);
            c.fibre_mm = std::min(c.fibre_mm, f.used.fibre_mm);
        }
        fed(f.used.pla_mm - c.pla_mm, f.used.fibre_mm - c.fibre_mm);
        c.pla_mm = f.used.pla_mm;
        c.fibre_mm = f.used.fibre_mm;
        if (f.layer == saved_layer_) return;
        saved_layer_ = f.layer;
        save();
    }
    const json needs = queue_needs();
    std::lock_guard lock(mu_);
    publish(needs);
}

void SpoolsComponent::commit(const SpoolState& before) {
    try {
        write_spools(file_, state_);
        unsaved_ = false;
    } catch (const std::exception& e) {
        state_ = before;
        throw ApiError::unavailable("the spools cannot be saved: " + std::string(e.what()));
    }
}

void SpoolsComponent::save() {
    try {
        write_spools(file_, state_);
        unsaved_ = false;
    } catch (const std::exception& e) {
        spdlog::error("spools.not_saved {}: the counts hold in memory until the next save", e.what());
    }
}

json SpoolsComponent::queue_needs() const {
    double fibre = 0, pla = 0;
    int unplanned = 0;
    const auto queued = queue_.queued();
    for (std::int64_t id : queued) {
        if (const auto u = jobs::planned_use(jobs_.store().plan_dir(id))) {
            fibre += u->fibre_m;
            pla += u->pla_m;
        } else {
            ++unplanned;
        }
    }
    return {{"jobs", queued.size()}, {"fibre_m", fibre}, {"pla_m", pla}, {"still_planning", unplanned}};
}

void SpoolsComponent::publish(const json& needs) {
    endpoints_.publish({.topic = api::topic::spools,
                        .method = api::notify::spools,
                        .params = view(needs),
                        .delivery = api::Delivery::every});
}

json SpoolsComponent::view(const json& needs) const {
    json spools = json::array();
    for (const std::string& tool : {std::string("T0"), std::string("T1")}) {
        json s = {{"tool", tool}, {"role", tool == fibre_tool_ ? "fibre" : "pla"}};
        const auto it = state_.spools.find(tool);
        s["loaded"] = it != state_.spools.end();
        if (it != state_.spools.end()) {
            const Spool& sp = it->second;
            s.update({{"material", sp.material},
                      {"tow", sp.tow},
                      {"lot", sp.lot},
                      {"diameter_mm", sp.diameter_mm ? json(*sp.diameter_mm) : json(nullptr)},
                      {"loaded_at", sp.loaded_at},
                      {"loaded_m", sp.loaded_mm / 1000.0},
                      {"used_m", sp.used_mm / 1000.0},
                      {"remaining_mm", sp.remaining_mm()},
                      {"remaining_m", sp.remaining_mm() / 1000.0}});
        }
        spools.push_back(s);
    }
    json v = {{"spools", spools},
              {"check", to_string(config_.check)},
              {"margin_percent", config_.margin_percent},
              {"margin_m", config_.margin_m},
              {"queue_needs", needs}};
    if (!note_.empty()) v["note"] = note_;
    return v;
}

}  // namespace fibrecell::daemon::spools
