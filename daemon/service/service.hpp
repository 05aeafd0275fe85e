#pragma once
// fibrecelld's service: its start-up and shut-down (docs/service.md). It builds the API server and
// the dashboard, and the components that own the cell's state and answer the API (docs/layout.md,
// "Components"): Cell (the devices), Jobs (the store and planning), Printer (the print on the
// cell) and Log, each registering its own methods and events. Everything runs on the caller's
// io_context except planning and printing, which have their own threads; a bad request is refused
// and changes nothing, a failed job never takes the service or another job down.

#include "config/directory_owner.hpp"
#include "daemon/api/api_config.hpp"
#include "daemon/api/api_server.hpp"
#include "daemon/cell/cell_config.hpp"
#include "daemon/component/component.hpp"
#include "daemon/http/http_server.hpp"
#include "daemon/jobs/jobs_config.hpp"
#include "daemon/printer/print_runner.hpp"
#include "daemon/history/history_config.hpp"
#include "daemon/queue/queue_config.hpp"
#include "daemon/spools/spools_config.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace fibrecell::daemon::printer {
class PrinterComponent;
}

namespace fibrecell::daemon::service {

struct ServiceConfig {
    CellConfig cell;
    api::ApiConfig api;
    jobs::JobsConfig jobs;
    printer::PrintRunnerOptions print;
    queue::QueueConfig queue;
    history::HistoryConfig history;
    spools::SpoolsConfig spools;
};

// The cell YAML with the service's sections (api:, jobs:, print:); throws config::ConfigError.
ServiceConfig load_service_config(const std::string& path);

class Service {
  public:
    // Builds the components and registers their endpoints; nothing is loaded, started or bound.
    Service(boost::asio::io_context& io, ServiceConfig config);
    ~Service();
    Service(const Service&) = delete;
    Service& operator=(const Service&) = delete;

    // Loads the jobs (interrupted prints come back `interrupted`), starts the devices, listens,
    // re-queues unfinished plans and connects the devices (a device that is not there yet is
    // reported in cell.status, not fatal). Throws api::ApiStartError when the socket cannot be
    // bound.
    void start();
    // SIGHUP: applies the settings that need no device or listener change (log level, API limits
    // and token); returns what was applied or why nothing was.
    std::string reload(const ServiceConfig& next);
    // SIGTERM: no new requests, planning stopped (re-queued on the next start), a running print
    // paused and left for resume, devices disconnected, the socket removed. False: planning was
    // still inside one step after jobs.stop_grace_s; the caller ends the process at once
    // (std::_Exit), not waiting for it, so that the stop keeps within systemd's timeout.
    bool stop();

    // For systemd's STATUS= line, twice a second while the service runs.
    std::string one_line_status() const;
    void on_status_line(std::function<void(const std::string&)> f) { status_line_ = std::move(f); }

    const api::ApiServer& api() const { return *api_; }
    const http::HttpServer* dashboard() const { return http_.get(); }  // null when api.http is off
    // The printer's hooks, for a start gate of a test's own (tests/service/registry_test.cpp).
    printer::PrinterComponent& printer() { return *printer_; }

  private:
    // Adds a component at the end of the list (it starts after, and stops before, those above).
    template <class C, class... Args>
    C& add(const std::string& name, Args&&... args);
    void register_server_info();
    void report_status();

    boost::asio::io_context& io_;
    ServiceConfig config_;
    std::unique_ptr<config::DirectoryLock> state_lock_;  // held while the service runs
    std::unique_ptr<api::ApiServer> api_;
    std::unique_ptr<http::HttpServer> http_;  // the dashboard (api.http), after api_
    std::vector<std::unique_ptr<component::Component>> components_;  // in start order
    std::size_t started_ = 0;  // how many of them start() reached
    printer::PrinterComponent* printer_ = nullptr;
    boost::asio::steady_timer status_timer_;
    std::function<void(const std::string&)> status_line_;
    bool stopping_ = false;
};

}  // namespace fibrecell::daemon::service
