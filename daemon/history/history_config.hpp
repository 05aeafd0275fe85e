#pragma once
// The `history:` section of the cell YAML: how long the cell's history keeps its records, and
// whether the plans of the jobs it forgets go with them (docs/history.md).
//
//   history:
//     keep: 1000          # records kept, the newest; older ones are dropped
//     keep_days: 365      # and none older than this (0: no age limit)
//     prune_plans: false  # true: a dropped record's job loses its plan directory (only a job
//                         # that ended: never one queued, printing or interrupted)

#include "config/yaml_section.hpp"

namespace fibrecell::daemon::history {

struct HistoryConfig {
    int keep = 1000;
    int keep_days = 365;
    bool prune_plans = false;
};

// Throws config::ConfigError naming the key ("history.keep").
HistoryConfig load_history_config(config::Section s);

}  // namespace fibrecell::daemon::history
