#pragma once
// The print queue's verbs (docs/queue.md): `fibrecell queue` (the bed and the queue), `queue add
// JOB [--position N]`, `queue move JOB POS`, `queue remove JOB`, `queue next`, `queue pause`,
// `queue resume`, and `fibrecell clear` (the operator's word that the bed is empty).

#include <CLI/CLI.hpp>

namespace fibrecell::tools {

void add_queue_commands(CLI::App& app, int& exit_code);

}  // namespace fibrecell::tools
