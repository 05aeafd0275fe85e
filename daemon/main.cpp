// fibrecelld: the print-cell service. This version validates the cell configuration; the socket
// API, jobs and device wiring are added by the service issue.

#include "config/logging.hpp"
#include "config/yaml_section.hpp"
#include "daemon/cell_config.hpp"

#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <iostream>

int main(int argc, char** argv) {
    CLI::App app{"fibrecelld - robotic continuous-fibre printing cell service"};
    std::string config_path;
    bool check_only = false;
    app.add_option("--config", config_path, "cell configuration (YAML)")->required();
    app.add_flag("--check-config", check_only, "validate the configuration and exit");
    CLI11_PARSE(app, argc, argv);

    fibrecell::daemon::CellConfig cell;
    try {
        cell = fibrecell::daemon::load_cell_config(config_path);
    } catch (const fibrecell::config::ConfigError& e) {
        std::cerr << "fibrecelld: " << e.what() << "\n";
        return 1;
    }
    if (check_only) {
        std::cout << config_path << ": configuration is valid\n";
        return 0;
    }
    fibrecell::config::setup_logging(cell.log_level);
    spdlog::error(
        "service.unavailable the service loop is not part of this build yet; "
        "use `fibrecell plan` for offline planning");
    return 3;
}
