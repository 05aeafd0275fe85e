#include "tools/fibrecell/plan_command.hpp"

#include <iostream>
#include <memory>
#include <string>

namespace fibrecell::tools {

void add_plan_command(CLI::App& app, int& exit_code) {
    struct Args {
        std::string job;
        std::string out;
    };
    auto args = std::make_shared<Args>();
    auto* cmd = app.add_subcommand("plan", "plan a job offline and write the plan directory");
    cmd->add_option("job", args->job, "job file (YAML)")->required();
    cmd->add_option("--out", args->out, "plan directory to write")->required();
    cmd->callback([args, &exit_code] {
        std::cerr << "fibrecell plan: not wired yet\n";
        exit_code = 1;
    });
}

}  // namespace fibrecell::tools
