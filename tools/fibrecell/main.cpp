// fibrecell: the operator's command-line client: offline planning and the service's verbs.

#include "config/build_info.hpp"
#include "config/logging.hpp"
#include "tools/fibrecell/compare_command.hpp"
#include "tools/fibrecell/history_command.hpp"
#include "tools/fibrecell/plan_command.hpp"
#include "tools/fibrecell/queue_commands.hpp"
#include "tools/fibrecell/service_commands.hpp"
#include "tools/fibrecell/spool_command.hpp"

#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
    CLI::App app{"fibrecell - plan and print continuous-fibre parts"};
    app.set_version_flag("--version", "fibrecell " + fibrecell::config::build_name());
    app.require_subcommand(1);
    bool verbose = false;
    app.add_flag("-v,--verbose", verbose, "log planner details to stderr");
    int exit_code = 0;
    fibrecell::tools::add_plan_command(app, exit_code);
    fibrecell::tools::add_compare_command(app, exit_code);
    fibrecell::tools::add_service_commands(app, exit_code);
    fibrecell::tools::add_queue_commands(app, exit_code);
    fibrecell::tools::add_history_command(app, exit_code);
    fibrecell::tools::add_spool_command(app, exit_code);
    app.parse_complete_callback(
        [&] { fibrecell::config::setup_logging(verbose ? "info" : "warn"); });
    CLI11_PARSE(app, argc, argv);
    return exit_code;
}
