// fibrecell: the operator's command-line client.

#include "tools/fibrecell/plan_command.hpp"

#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
    CLI::App app{"fibrecell - plan and print continuous-fibre parts"};
    app.require_subcommand(1);
    int exit_code = 0;
    fibrecell::tools::add_plan_command(app, exit_code);
    CLI11_PARSE(app, argc, argv);
    return exit_code;
}
