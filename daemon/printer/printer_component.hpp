#pragma once
// Printer, the component that owns the print on the cell (docs/layout.md, "Components"): the
// print runner (one print at a time on its thread: pre-flight, the sync engine, recovery) and the
// heaters' policy. It answers job.start, job.pause, job.resume and job.abort, publishes the print's
// notify.job_progress, adds the live print to a job's view and to cell.status, and aborts its
// print at cell.estop.
//
// Hook for the components above it:
//   add_start_gate  a check that must pass before any print starts (job.start, job.resume of an
//                   interrupted job, a job submitted with `start` once planned, the queue's next
//                   job): a gate that answers a reason refuses the start with it, and nothing
//                   moves.
//   start_print     starts a planned job as job.start does (the gates first), for a component
//                   that starts jobs of its own (the print queue).
//   on_print_finished  a print left the cell (completed or aborted) and its figures are written
//                   (result.json, the journal's last `used`): the history takes them from there.
//   on_feed         the filament the print has taken so far, as the board's count grows (the
//                   spools subtract it).

#include "daemon/cell/cell_config.hpp"
#include "daemon/component/component.hpp"
#include "daemon/devices/cell_component.hpp"
#include "daemon/jobs/jobs_component.hpp"
#include "daemon/printer/print_runner.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace fibrecell::daemon::printer {

class PrinterComponent : public component::Component {
  public:
    // Why `record` must not start now, or nullopt. Called on the API's strand or a planning
    // thread.
    using StartGate = std::function<std::optional<std::string>(const jobs::JobRecord& record)>;

    PrinterComponent(jobs::JobsComponent& jobs, devices::CellComponent& cell, const CellConfig& config,
                     PrintRunnerOptions options);
    ~PrinterComponent() override;

    void add_start_gate(StartGate gate);  // before start()
    // On the runner's thread, after result.json; before start().
    void on_print_finished(std::function<void(std::int64_t id)> f);
    void on_feed(PrintRunner::FeedObserver f);  // on the runner's thread; before start()

    // job.start: the gates, the store's start, then the runner. Throws api::ApiError (conflict
    // with the gate's or the store's reason, not found). `by`: who started it (the record's
    // started_by).
    jobs::JobRecord start_print(std::int64_t id, const std::string& by);

    void register_endpoints(component::Endpoints& endpoints) override;
    void start() override;
    void stop() override;  // a running print is paused, to resume after the next start

    // For systemd's STATUS= line: "idle, 3 jobs" or "printing job 4, layer 2/26".
    std::string one_line_status() const;

  private:
    // The first gate's reason why `record` must not start, or nullopt.
    std::optional<std::string> held_at_gate(const jobs::JobRecord& record) const;
    // The call's `job`; without one, the job on the cell (pause, resume, abort).
    std::int64_t job_or_on_cell(const nlohmann::json& params, const api::CallContext& ctx) const;
    void start_when_planned(const jobs::JobRecord& record);

    jobs::JobsComponent& jobs_;
    devices::CellComponent& cell_;
    CellConfig config_;
    PrintRunnerOptions options_;
    component::Endpoints endpoints_;
    std::vector<StartGate> gates_;
    std::vector<std::function<void(std::int64_t)>> finished_;
    std::vector<PrintRunner::FeedObserver> feed_;
    std::mutex start_mu_;  // a gate's answer and the start it allows, as one step
    // Jobs submitted with `start` whose start was refused once planned, and why: their view says
    // so (`start_refused`), so that a watching client need not wait for a start that will not come.
    mutable std::mutex refused_mu_;
    std::map<std::int64_t, std::string> start_refused_;
    std::unique_ptr<PrintRunner> runner_;
};

}  // namespace fibrecell::daemon::printer
