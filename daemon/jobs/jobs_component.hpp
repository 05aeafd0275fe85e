#pragma once
// Jobs, the component that owns the jobs (docs/layout.md, "Components"): the store with each
// job's folder and journal, and the planning workers with their pool. It answers job.submit,
// job.list, job.get, job.replan and job.remove, publishes notify.job_state and the planning share
// of notify.job_progress, and serves a job's plan files to the dashboard.
//
// Hooks for the components above it:
//   add_job_view  what a job's view (job.get, job.list, notify.job_state) says besides the store's
//                 record and the plan's figures; the printer adds the live print progress.
//   on_planned    a job's planning ended; the printer starts one submitted with `start`.
//   on_change     a job's state changed (the store's every change, after notify.job_state went
//                 out); the print queue follows its jobs and the cell's bed with it.

#include "daemon/cell/cell_config.hpp"
#include "daemon/component/component.hpp"
#include "daemon/jobs/job_store.hpp"
#include "daemon/jobs/jobs_config.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace fibrecell::daemon::jobs {

class PlanRunner;
class ThreadPool;

class JobsComponent : public component::Component {
  public:
    using JobView = std::function<void(const JobRecord& record, nlohmann::json& view)>;
    using Planned = std::function<void(const JobRecord& record)>;
    using Changed = std::function<void(const JobRecord& record)>;

    JobsComponent(const CellConfig& cell, const JobsConfig& config);
    ~JobsComponent() override;

    void add_job_view(JobView view);   // before start()
    void on_planned(Planned planned);  // before start(); called on a planning thread
    // Before start(); called on the thread that changed the job (the API's, a planning worker,
    // the print runner), never with the store's lock held.
    void on_change(Changed changed);

    void register_endpoints(component::Endpoints& endpoints) override;
    void start() override;  // loads the jobs (interrupted prints come back `interrupted`)
    void serve() override;  // plans what was left unplanned
    void stop() override;   // cancels planning (re-queued on the next start)
    bool join(Deadline deadline) override;

    // After start():
    JobStore& store() { return *store_; }
    // The job as job.get answers it.
    nlohmann::json job_json(const JobRecord& record) const;
    // job.abort of a job still planning.
    JobRecord abort_planning(std::int64_t id);
    // What a job view hook adds changed without a state change (a start refused once planned):
    // notify.job_state goes out again, so that watchers need not poll for it.
    void view_changed(std::int64_t id);

  private:
    void publish_job(const JobRecord& record);

    CellConfig cell_;
    JobsConfig config_;
    component::Endpoints endpoints_;
    std::vector<JobView> views_;
    std::vector<Planned> planned_;
    std::vector<Changed> changed_;
    std::vector<std::int64_t> to_plan_;  // found unplanned by start()
    std::unique_ptr<JobStore> store_;
    std::unique_ptr<ThreadPool> planning_pool_;  // before planner_, which uses it
    std::unique_ptr<PlanRunner> planner_;
};

}  // namespace fibrecell::daemon::jobs
