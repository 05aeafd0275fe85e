// fibrecelld: the print-cell service (docs/service.md). Runs until SIGTERM/SIGINT; SIGHUP re-reads
// the cell YAML and applies what needs no restart. Under systemd (Type=notify) it reports READY
// once the socket listens, a STATUS line, and pings the watchdog from its event loop.

#include "config/build_info.hpp"
#include "config/logging.hpp"
#include "config/yaml_section.hpp"
#include "daemon/service/service.hpp"
#include "daemon/service/systemd_notify.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <sys/stat.h>

#include <csignal>
#include <cstdlib>
#include <iostream>

namespace {

using fibrecell::daemon::service::ServiceConfig;

struct Overrides {
    std::string state_dir, socket, dashboard_token_file;
};

ServiceConfig load(const std::string& path, const Overrides& o) {
    ServiceConfig c = fibrecell::daemon::service::load_service_config(path);
    if (!o.state_dir.empty()) c.cell.state_dir = o.state_dir;
    if (!o.socket.empty()) c.api.socket_path = o.socket;
    if (!o.dashboard_token_file.empty()) {
        c.api.http.enabled = true;
        try {
            c.api.http.token = fibrecell::api::read_token_file(o.dashboard_token_file);
        } catch (const std::runtime_error& e) {
            throw fibrecell::config::ConfigError(std::string("--dashboard-token-file: ") + e.what());
        }
    }
    return c;
}

// Pings systemd's watchdog from the io_context: a stuck loop stops the pings.
void watchdog(boost::asio::steady_timer& timer, fibrecell::daemon::service::SystemdNotifier& sd,
              std::chrono::microseconds period) {
    sd.watchdog();
    timer.expires_after(period);
    timer.async_wait([&timer, &sd, period](const boost::system::error_code& ec) {
        if (!ec) watchdog(timer, sd, period);
    });
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"fibrecelld - robotic continuous-fibre printing cell service"};
    app.set_version_flag("--version", "fibrecelld " + fibrecell::config::build_name());
    std::string config_path;
    bool check_only = false;
    Overrides overrides;
    app.add_option("--config", config_path, "cell configuration (YAML)")->required();
    app.add_flag("--check-config", check_only, "validate the configuration and exit");
    app.add_option("--state-dir", overrides.state_dir, "job folders (overrides state_dir)");
    app.add_option("--socket", overrides.socket, "the API's Unix socket (overrides api.socket)");
    app.add_option("--dashboard-token-file", overrides.dashboard_token_file,
                   "serve the dashboard (api.http) with the token on this file's first line");
    CLI11_PARSE(app, argc, argv);

    ServiceConfig config;
    try {
        config = load(config_path, overrides);
    } catch (const fibrecell::config::ConfigError& e) {
        std::cerr << "fibrecelld: " << e.what() << "\n";
        return 1;
    }
    if (check_only) {
        std::cout << config_path << ": configuration is valid\n";
        return 0;
    }
    fibrecell::config::setup_logging(config.cell.log_level);
    // Job folders 0750, files 0640, whoever starts the service (the unit's UMask says the same).
    ::umask(027);
    std::signal(SIGPIPE, SIG_IGN);  // a client that went away is an error on its socket, not a kill

    boost::asio::io_context io;
    fibrecell::daemon::service::SystemdNotifier sd;
    fibrecell::daemon::service::Service service(io, config);
    try {
        service.start();
    } catch (const std::exception& e) {
        spdlog::critical("service.start_failed {}", e.what());
        std::cerr << "fibrecelld: " << e.what() << "\n";
        return 2;
    }
    spdlog::info("service.ready cell={} socket={} state_dir={}", config.cell.name,
                 config.api.socket_path, config.cell.state_dir);
    std::cout << "fibrecelld: listening on " << config.api.socket_path << std::endl;
    if (const auto* dashboard = service.dashboard())
        std::cout << "fibrecelld: dashboard on http://" << config.api.http.host << ":"
                  << dashboard->port() << "/" << std::endl;
    sd.ready(service.one_line_status());
    service.on_status_line([&sd](const std::string& line) { sd.status(line); });

    boost::asio::steady_timer watchdog_timer(io);
    if (const auto period = sd.watchdog_period()) watchdog(watchdog_timer, sd, *period);

    boost::asio::signal_set reload_signal(io, SIGHUP);
    std::function<void()> wait_reload = [&] {
        reload_signal.async_wait([&](const boost::system::error_code& ec, int) {
            if (ec) return;
            sd.reloading();
            try {
                const std::string what = service.reload(load(config_path, overrides));
                spdlog::info("service.reloaded {}", what);
            } catch (const std::exception& e) {
                spdlog::error("service.reload_refused {} (the running configuration stays)", e.what());
            }
            sd.ready(service.one_line_status());
            wait_reload();
        });
    };
    wait_reload();

    boost::asio::signal_set stop_signals(io, SIGTERM, SIGINT);
    bool stopped_cleanly = true;
    stop_signals.async_wait([&](const boost::system::error_code& ec, int signal) {
        if (ec) return;
        spdlog::info("service.stopping signal={}", signal);
        sd.stopping("stopping: pausing any print and saving jobs");
        stopped_cleanly = service.stop();
        reload_signal.cancel();
        watchdog_timer.cancel();
        io.stop();
    });

    io.run();
    if (!stopped_cleanly) {
        // A planner thread is inside a step it cannot leave (a factorisation): the jobs and the
        // devices are already saved and stopped; ending here keeps the stop within systemd's
        // TimeoutStopSec instead of a SIGKILL later.
        spdlog::shutdown();
        std::_Exit(0);
    }
    return 0;
}
