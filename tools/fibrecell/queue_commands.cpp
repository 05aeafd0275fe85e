#include "tools/fibrecell/queue_commands.hpp"

#include "tools/fibrecell/job_view.hpp"
#include "tools/fibrecell/service_connection.hpp"

#include <cstdint>
#include <memory>
#include <string>

namespace fibrecell::tools {
namespace {

using nlohmann::json;

// One verb of `queue`: the method, its params from the command line, the queue shown after.
void add_queue_verb(CLI::App& queue, int& exit_code, const std::string& verb,
                    const std::string& help, const std::string& method, bool takes_job,
                    bool takes_position, bool position_required) {
    auto* cmd = queue.add_subcommand(verb, help);
    auto c = std::make_shared<Connection>();
    auto id = std::make_shared<std::int64_t>(0);
    auto position = std::make_shared<std::int64_t>(0);
    if (takes_job) cmd->add_option("job", *id, "job id")->required();
    if (takes_position) {
        auto* opt = position_required
                        ? cmd->add_option("position", *position, "1 is the next to print")->required()
                        : cmd->add_option("--position", *position, "where in the queue (default: last)");
        opt->check(CLI::PositiveNumber);
    }
    add_connection_options(*cmd, *c);
    cmd->callback([&exit_code, c, id, position, method] {
        guarded(exit_code, [&] {
            json params = json::object();
            if (*id != 0) params["job"] = *id;
            if (*position != 0) params["position"] = *position;
            api::ApiClient client = c->connect();
            const json answer = client.call(method, params);
            print(*c, answer, queue_table(answer));
            return 0;
        });
    });
}

}  // namespace

void add_queue_commands(CLI::App& app, int& exit_code) {
    auto* queue = app.add_subcommand("queue", "the print queue and the bed (without a verb: show them)");
    auto c = std::make_shared<Connection>();
    add_connection_options(*queue, *c);
    add_queue_verb(*queue, exit_code, "add", "queue a planned (or planning) job", "queue.add", true,
                   true, false);
    add_queue_verb(*queue, exit_code, "move", "move a queued job to a position", "queue.move",
                   true, true, true);
    add_queue_verb(*queue, exit_code, "remove", "take a job out of the queue (the job stays)",
                   "queue.remove", true, false, false);
    add_queue_verb(*queue, exit_code, "next", "start the next queued job now", "queue.next", false,
                   false, false);
    add_queue_verb(*queue, exit_code, "pause", "hold the queue: nothing starts from it by itself",
                   "queue.pause", false, false, false);
    add_queue_verb(*queue, exit_code, "resume", "let the queue start jobs again", "queue.resume",
                   false, false, false);
    queue->callback([&exit_code, c, queue] {
        if (!queue->get_subcommands().empty()) return;  // a verb ran
        guarded(exit_code, [&] {
            api::ApiClient client = c->connect();
            const json answer = client.call("queue.list");
            print(*c, answer, queue_table(answer));
            return 0;
        });
    });

    auto* clear = app.add_subcommand(
        "clear", "say the bed is clear: the last print's part is off (the next job may start)");
    auto cc = std::make_shared<Connection>();
    add_connection_options(*clear, *cc);
    clear->callback([&exit_code, cc] {
        guarded(exit_code, [&] {
            api::ApiClient client = cc->connect();
            const json answer = client.call("cell.clear");
            print(*cc, answer, "cell cleared\n" + queue_table(answer));
            return 0;
        });
    });
}

}  // namespace fibrecell::tools
