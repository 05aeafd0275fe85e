#pragma once
// History, the component that owns the cell's history (docs/history.md): one record for every
// job that ended — completed, aborted, failed or interrupted — with who submitted and started it,
// its times, layers, the filament the board fed beside the plan's, the cut error and the outcome.
// It answers history.list (JSON or CSV) and publishes notify.history on topic "history".
//
// On the hooks of the components below it: the jobs' changes (a job reached an end) and the
// printer's on_print_finished (its figures are written now: the record is taken again, whole).
// A job records once; ending again after a resume replaces its record. At start-up the jobs that
// ended while the service was down (interrupted by a crash) are recorded. The records are kept
// within history.keep and history.keep_days; with history.prune_plans the plans of the jobs whose
// records go are deleted too (only of jobs that ended).

#include "daemon/cell/cell_config.hpp"
#include "daemon/component/component.hpp"
#include "daemon/history/history_config.hpp"
#include "daemon/history/history_record.hpp"
#include "daemon/jobs/jobs_component.hpp"
#include "daemon/printer/printer_component.hpp"

#include <filesystem>
#include <mutex>
#include <vector>

namespace fibrecell::daemon::history {

class HistoryComponent : public component::Component {
  public:
    HistoryComponent(jobs::JobsComponent& jobs, printer::PrinterComponent& printer,
                     const CellConfig& cell, HistoryConfig config);

    void register_endpoints(component::Endpoints& endpoints) override;
    void start() override;  // reads history.jsonl; records the jobs that ended meanwhile

  private:
    // Records `job` when it is at an end (replacing its earlier record); saves and publishes.
    void take(const jobs::JobRecord& job);
    // Drops what history.keep and keep_days do not keep (and their plans); lock held.
    void retain();
    void save();  // lock held; a failure is logged, the records hold in memory

    jobs::JobsComponent& jobs_;
    HistoryConfig config_;
    std::filesystem::path file_;
    component::Endpoints endpoints_;

    mutable std::mutex mu_;
    std::vector<HistoryRecord> records_;  // oldest first, one per job
};

}  // namespace fibrecell::daemon::history
