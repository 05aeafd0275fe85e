#pragma once
// Spools, the component that owns the spool loaded on each hotend (docs/spools.md): T0 the PLA
// hotend's filament, T1 the fibre. It answers spool.list, spool.load and spool.unload, publishes
// notify.spools on topic "spools", and adds the spools to cell.status.
//
// On the hooks of the components below it:
//   - the printer's on_feed: what a print took, by the board's own count, is taken off the spools
//     as it feeds; spools.json is saved at every layer, at the print's end and at a stop, so a
//     crash loses at most the layer's count in the file — and the next start charges what the
//     job's journal (saved every poll) shows beyond it, and says how much that was;
//   - the printer's start gate and the queue's admission check: a job that needs more than a
//     loaded spool holds (the plan's figure, less what the job fed already, plus the margin) is
//     refused with both figures (spools.check: refuse), or only warned of (warn).
// A hotend without a spool loaded is not checked: a cell that does not keep spools prints as
// before.

#include "daemon/cell/cell_config.hpp"
#include "daemon/component/component.hpp"
#include "daemon/devices/cell_component.hpp"
#include "daemon/jobs/jobs_component.hpp"
#include "daemon/printer/printer_component.hpp"
#include "daemon/queue/queue_component.hpp"
#include "daemon/spools/spool_state.hpp"
#include "daemon/spools/spools_config.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <mutex>
#include <optional>
#include <string>

namespace fibrecell::daemon::spools {

class SpoolsComponent : public component::Component {
  public:
    SpoolsComponent(jobs::JobsComponent& jobs, printer::PrinterComponent& printer,
                    queue::QueueComponent& queue, devices::CellComponent& cell,
                    const CellConfig& cell_config, SpoolsConfig config);

    void register_endpoints(component::Endpoints& endpoints) override;
    void start() override;  // reads spools.json; charges what the last job's journal adds
    bool join(Deadline deadline) override;  // saves: the print's last feed is in by now

  private:
    // Why `job` must not start or be queued with the spools as they are, or nullopt; a warning is
    // logged instead when spools.check is warn.
    std::optional<std::string> short_of(const jobs::JobRecord& job, const char* doing) const;
    // Takes filament off the loaded spools; lock held.
    void fed(double pla_mm, double fibre_mm);
    // A print's count grew: charged to the spools; saved and published at a new layer.
    void fed_and_saved(const printer::PrintRunner::Feed& feed);
    // An operator's change: saved, or undone and refused (ApiError unavailable). Lock held.
    void commit(const SpoolState& before);
    void save();  // lock held; a failure is logged, the state holds in memory
    // What the queued jobs' plans will feed. Takes the queue's lock: never call with ours held
    // (the queue asks short_of() with its lock held).
    nlohmann::json queue_needs() const;
    void publish(const nlohmann::json& needs);  // lock held
    nlohmann::json view(const nlohmann::json& needs) const;  // spool.list's answer; lock held

    jobs::JobsComponent& jobs_;
    queue::QueueComponent& queue_;
    SpoolsConfig config_;
    std::string pla_tool_, fibre_tool_;  // "T0", "T1" from the cell's extruder section
    std::filesystem::path file_;
    component::Endpoints endpoints_;

    mutable std::mutex mu_;
    SpoolState state_;
    int saved_layer_ = -1;   // the layer spools.json was last saved at
    bool unsaved_ = false;   // fed since the last save
    std::string note_;       // what the last start charged from a journal
};

}  // namespace fibrecell::daemon::spools
