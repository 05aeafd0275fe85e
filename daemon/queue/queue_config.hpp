#pragma once
// The `queue:` section of the cell YAML: what the print queue does once the operator has said
// the cell is clear (docs/queue.md).
//
//   queue:
//     auto_start: manual        # manual: the operator starts the next job (`fibrecell queue next`)
//                               # after_clear: the next queued job starts as soon as the cell is
//                               # clear, the queue not paused and the job planned

#include "config/yaml_section.hpp"

namespace fibrecell::daemon::queue {

enum class AutoStart { manual, after_clear };

struct QueueConfig {
    AutoStart auto_start = AutoStart::manual;
};

const char* to_string(AutoStart a);

// Throws config::ConfigError naming the key ("queue.auto_start").
QueueConfig load_queue_config(config::Section s);

}  // namespace fibrecell::daemon::queue
