#include "daemon/service/service.hpp"

#include "config/build_info.hpp"
#include "config/logging.hpp"
#include "daemon/devices/cell_component.hpp"
#include "daemon/history/history_component.hpp"
#include "daemon/jobs/jobs_component.hpp"
#include "daemon/log/log_component.hpp"
#include "daemon/printer/printer_component.hpp"
#include "daemon/printer/printer_config.hpp"
#include "daemon/queue/queue_component.hpp"
#include "daemon/spools/spools_component.hpp"

#include <spdlog/spdlog.h>

#include <unistd.h>

#include <ranges>

namespace fibrecell::daemon::service {

using nlohmann::json;

ServiceConfig load_service_config(const std::string& path) {
    ServiceConfig c;
    c.cell = load_cell_config(path, [&](config::Section& root) {
        c.api = api::load_api_config(root.section("api"));
        c.jobs = jobs::load_jobs_config(root.section("jobs"));
        c.print = printer::load_print_options(root.section("print"));
        c.queue = queue::load_queue_config(root.section("queue"));
        c.history = history::load_history_config(root.section("history"));
        c.spools = spools::load_spools_config(root.section("spools"));
    });
    return c;
}

template <class C, class... Args>
C& Service::add(const std::string& name, Args&&... args) {
    auto owned = std::make_unique<C>(std::forward<Args>(args)...);
    C& c = *owned;
    component::Endpoints endpoints(*api_, http_.get(), name);
    c.register_endpoints(endpoints);
    components_.push_back(std::move(owned));
    return c;
}

Service::Service(boost::asio::io_context& io, ServiceConfig config)
    : io_(io), config_(std::move(config)), status_timer_(io) {
    api_ = std::make_unique<api::ApiServer>(io_, config_.api);
    if (config_.api.http.enabled)
        http_ = std::make_unique<http::HttpServer>(io_, config_.api, *api_);
    register_server_info();

    // The components, in the order they depend on each other. A new one adds its line here and
    // registers on the hooks of those above it (daemon/component/component.hpp).
    auto& cell = add<devices::CellComponent>(
        "cell", io_, config_.cell,
        devices::CellComponentOptions{.connect_timeout = config_.print.connect_timeout,
                                      .realtime_priority = config_.print.realtime_priority});
    auto& jobs = add<jobs::JobsComponent>("jobs", config_.cell, config_.jobs);
    printer_ = &add<printer::PrinterComponent>("printer", jobs, cell, config_.cell, config_.print);
    auto& queue = add<queue::QueueComponent>("queue", jobs, *printer_, cell, config_.cell, config_.queue);
    add<history::HistoryComponent>("history", jobs, *printer_, config_.cell, config_.history);
    add<spools::SpoolsComponent>("spools", jobs, *printer_, queue, cell, config_.cell, config_.spools);
    add<logs::LogComponent>("log");
}

Service::~Service() { stop(); }

void Service::register_server_info() {
    api_->add_method(
        "server.info",
        [this](const json&, const api::CallContext&) {
            return json{{"service", "fibrecelld"},
                        {"version", config::build_version()},
                        {"commit", config::build_commit()},
                        {"cell", config_.cell.name},
                        {"simulated", config_.cell.simulated},
                        {"pid", static_cast<long>(::getpid())},
                        {"tcp_port", api_->tcp_port()},
                        {"http_port", http_ ? http_->port() : 0},
                        {"state_dir", config_.cell.state_dir}};
        },
        "service");
    api_->add_control_method("server.info");
}

void Service::start() {
    // The state directory is this service's alone: private, and locked against a second one.
    config::ensure_private_directory(config_.cell.state_dir, "state directory");
    if (!state_lock_)
        state_lock_ = std::make_unique<config::DirectoryLock>(
            config_.cell.state_dir, "fibrecelld pid " + std::to_string(::getpid()) +
                                        " (socket " + config_.api.socket_path + ")");
    for (; started_ < components_.size(); ++started_) components_[started_]->start();
    api_->start();
    if (http_) {
        try {
            http_->start();
        } catch (...) {
            api_->stop();
            throw;
        }
    }
    for (const auto& c : components_) c->serve();
    report_status();
}

std::string Service::reload(const ServiceConfig& next) {
    std::vector<std::string> ignored;
    if (next.cell.simulated != config_.cell.simulated) ignored.push_back("simulated");
    if (next.cell.state_dir != config_.cell.state_dir) ignored.push_back("state_dir");
    if (next.api.socket_path != config_.api.socket_path || next.api.tcp.enabled != config_.api.tcp.enabled ||
        next.api.tcp.port != config_.api.tcp.port || next.api.tcp.host != config_.api.tcp.host)
        ignored.push_back("api listeners");
    config::setup_logging(next.cell.log_level);
    api_->update_limits(next.api);
    if (http_) http_->update(next.api);
    if (next.api.http.enabled != config_.api.http.enabled || next.api.http.port != config_.api.http.port ||
        next.api.http.host != config_.api.http.host)
        ignored.push_back("api.http listener");
    config_.api = next.api;
    config_.cell.log_level = next.cell.log_level;
    std::string what = "applied log_level, api limits and token";
    if (!ignored.empty()) {
        what += "; needs a restart: ";
        for (std::size_t i = 0; i < ignored.size(); ++i) what += (i ? ", " : "") + ignored[i];
    }
    return what;
}

bool Service::stop() {
    if (stopping_ || started_ == 0) return true;
    stopping_ = true;
    status_timer_.cancel();
    if (http_) http_->stop();
    api_->stop();
    const auto started = std::views::counted(components_.begin(), static_cast<long>(started_));
    for (const auto& c : started | std::views::reverse) c->stop();
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(config_.jobs.stop_grace_s));
    bool joined = true;
    for (const auto& c : started | std::views::reverse) joined = c->join(deadline) && joined;
    if (joined) spdlog::info("service.stopped");
    return joined;
}

void Service::report_status() {
    status_timer_.expires_after(std::chrono::milliseconds(500));
    status_timer_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || stopping_) return;
        if (status_line_) status_line_(one_line_status());
        report_status();
    });
}

std::string Service::one_line_status() const {
    return started_ == components_.size() ? printer_->one_line_status() : "starting";
}

}  // namespace fibrecell::daemon::service
