#pragma once
// The `jobs:` section of the cell YAML: where job folders live and how planning runs.
//
//   jobs:
//     planning_workers: 1              # jobs planned at the same time
//     planner_threads: 0               # the planning pool, shared by the workers (0: a core each)
//     planner_nice: 10                 # planning's CPU priority below the print's (0..19)
//     max_queued: 16                   # jobs waiting for or in planning; more are refused
//     keep_completed: 50               # ended jobs kept; the oldest beyond are removed
//     plan_retries: 3                  # restarts during one job's planning before it fails
//     stop_grace_s: 10                 # a service stop waits this long for planning to stop;
//                                      # past it, it exits without waiting (docs/service.md)

#include "config/yaml_section.hpp"

#include <string>

namespace fibrecell::daemon::jobs {

struct JobsConfig {
    int planning_workers = 1;  // 1..16
    int planner_threads = 0;   // 0..256
    int planner_nice = 10;     // 0..19
    int max_queued = 16;       // 1..10000
    int keep_completed = 50;   // 0..100000
    int plan_retries = 3;      // 0..10
    double stop_grace_s = 10;  // 0..25: within systemd's TimeoutStopSec (30 s) with the rest
};

// Reads and checks the section (ranges, unknown keys; state_dir belongs to the top level);
// throws config::ConfigError naming the key ("jobs.planning_workers").
JobsConfig load_jobs_config(config::Section s);

}  // namespace fibrecell::daemon::jobs
