#pragma once
// Queue, the component that owns the print queue and the clear-cell rule (docs/queue.md):
// planned jobs wait in order for the cell; when a print ends its part is on the bed, and no job
// starts, queued or by hand, until the operator says the cell is clear (cell.clear). It answers
// queue.list, queue.add, queue.move, queue.remove, queue.pause, queue.resume, queue.next and
// cell.clear, publishes notify.queue, and adds the bed and the queue to cell.status.
//
// On the hooks of the components below it: a start gate on the printer (the bed must be clear,
// but for the re-entry of the interrupted job whose part is on it), the jobs' changes (a queued
// job that started, ended or went away leaves the queue; a print that ends holds the bed), and a
// part of cell.status.
//
// Hooks for the components above it:
//   add_admission_check  a check queue.add asks before a job joins the queue (the spools: is
//                        there filament enough); a reason refuses it.
//   queued               the jobs waiting, in print order.

#include "daemon/cell/cell_config.hpp"
#include "daemon/api/params.hpp"
#include "daemon/component/component.hpp"
#include "daemon/devices/cell_component.hpp"
#include "daemon/jobs/jobs_component.hpp"
#include "daemon/printer/printer_component.hpp"
#include "daemon/queue/queue_config.hpp"
#include "daemon/queue/queue_state.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <set>
#include <string>

namespace fibrecell::daemon::queue {

class QueueComponent : public component::Component {
  public:
    using AdmissionCheck = std::function<std::optional<std::string>(const jobs::JobRecord&)>;

    QueueComponent(jobs::JobsComponent& jobs, printer::PrinterComponent& printer,
                   devices::CellComponent& cell, const CellConfig& cell_config, QueueConfig config);

    void add_admission_check(AdmissionCheck check);  // before start()
    std::vector<std::int64_t> queued() const;

    void register_endpoints(component::Endpoints& endpoints) override;
    void start() override;  // reads queue.json and squares it with the jobs as loaded
    void serve() override;  // after_clear: the next job, when it is due

  private:
    // Why `record` must not start now (the bed holds another job's part), or nullopt.
    std::optional<std::string> held_by_bed(const jobs::JobRecord& record) const;
    void job_changed(const jobs::JobRecord& record);
    // The queue.list answer; lock held.
    nlohmann::json view() const;
    // An API call's change: saved, or undone and refused (ApiError unavailable); then published.
    // Lock held.
    void commit(const QueueState& before);
    // A change the jobs made: saved (a failure is logged; the state holds in memory and the next
    // change tries again) and published. Lock held.
    void changed();
    void publish() const;  // notify.queue; lock held
    // after_clear: starts the next queued job when the bed is clear, the queue not paused, the job
    // planned and the cell free. Lock not held.
    void start_next_if_due();
    // An API call's answer after a change: the next job started if due, then the queue.
    nlohmann::json next_if_due_then_view();
    // Queued jobs the store no longer has (job.remove) leave the queue. Lock held.
    void drop_gone_jobs();
    // Nothing goes to position 1 before a next job that is starting. Lock held.
    void refuse_before_a_starting_head(std::int64_t position) const;
    // The call's `job`, which must be queued (else a conflict that says where it is), and its
    // place (0: the next). Lock held.
    std::int64_t queued_job(api::ParamReader& params, std::size_t* position);

    jobs::JobsComponent& jobs_;
    printer::PrinterComponent& printer_;
    QueueConfig config_;
    std::filesystem::path file_;
    component::Endpoints endpoints_;
    std::vector<AdmissionCheck> admission_checks_;

    std::mutex start_mu_;  // start_next_if_due, one at a time
    mutable std::mutex mu_;
    QueueState state_;
    std::set<std::int64_t> starting_;   // queued jobs the store has starting
    std::int64_t queue_started_ = 0;    // the job the queue itself is starting
    std::int64_t started_on_clear_ = 0; // a job starting on a clear bed (a refusal clears it again)
};

}  // namespace fibrecell::daemon::queue
