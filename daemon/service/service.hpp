#pragma once
// fibrecelld's service: the socket API's methods (docs/contracts.md) over the job store, the
// planning workers, the cell's devices and the print runner (docs/service.md). Everything runs on
// the caller's io_context except planning and printing, which have their own threads; a bad request
// is refused and changes nothing, a failed job never takes the service or another job down.

#include "config/directory_owner.hpp"
#include "daemon/api/api_config.hpp"
#include "daemon/api/api_server.hpp"
#include "daemon/cell/cell_config.hpp"
#include "daemon/http/http_server.hpp"
#include "daemon/jobs/job_store.hpp"
#include "daemon/jobs/jobs_config.hpp"
#include "daemon/jobs/plan_runner.hpp"
#include "daemon/jobs/thread_pool.hpp"
#include "daemon/service/cell_devices.hpp"
#include "daemon/service/print_runner.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <nlohmann/json.hpp>

#include <functional>
#include <memory>
#include <string>

namespace fibrecell::daemon::service {

struct ServiceConfig {
    CellConfig cell;
    api::ApiConfig api;
    jobs::JobsConfig jobs;
    PrintRunnerOptions print;
};

// The cell YAML with the service's sections (api:, jobs:, print:); throws config::ConfigError.
ServiceConfig load_service_config(const std::string& path);

class Service {
  public:
    Service(boost::asio::io_context& io, ServiceConfig config);
    ~Service();
    Service(const Service&) = delete;
    Service& operator=(const Service&) = delete;

    // Loads the jobs (interrupted prints come back `interrupted`), re-queues unfinished plans,
    // starts listening and connects the devices (a device that is not there yet is reported in
    // cell.status, not fatal). Throws api::ApiStartError when the socket cannot be bound.
    void start();
    // SIGHUP: applies the settings that need no device or listener change (log level, API limits
    // and token, heater time-out); returns what was applied or why nothing was.
    std::string reload(const ServiceConfig& next);
    // SIGTERM: no new requests, planning stopped (re-queued on the next start), a running print
    // paused and left for resume, devices disconnected, the socket removed. False: planning was
    // still inside one step after jobs.stop_grace_s; the caller ends the process at once
    // (std::_Exit), not waiting for it, so that the stop keeps within systemd's timeout.
    bool stop();

    // For systemd's STATUS= line and the watchdog.
    std::string one_line_status() const;
    void on_status_line(std::function<void(const std::string&)> f) { status_line_ = std::move(f); }

    const api::ApiServer& api() const { return *api_; }
    const http::HttpServer* dashboard() const { return http_.get(); }  // null when api.http is off

  private:
    void register_methods();
    void start_dashboard();
    nlohmann::json job_json(const jobs::JobRecord& r) const;
    nlohmann::json cell_status() const;
    std::int64_t job_param(const nlohmann::json& params, const api::CallContext& ctx,
                           bool default_to_current) const;
    void publish_job(const jobs::JobRecord& r);
    void tick();

    boost::asio::io_context& io_;
    ServiceConfig config_;
    std::unique_ptr<config::DirectoryLock> state_lock_;  // held while the service runs
    std::unique_ptr<api::ApiServer> api_;
    std::unique_ptr<http::HttpServer> http_;  // the dashboard (api.http), after api_
    std::unique_ptr<jobs::JobStore> store_;
    std::unique_ptr<CellDevices> devices_;
    std::unique_ptr<jobs::ThreadPool> planning_pool_;  // before planner_, which uses it
    std::unique_ptr<jobs::PlanRunner> planner_;
    std::unique_ptr<PrintRunner> printer_;
    boost::asio::steady_timer ticker_;
    std::function<void(const std::string&)> status_line_;
    bool stopping_ = false;
};

}  // namespace fibrecell::daemon::service
