#include "daemon/jobs/jobs_config.hpp"


namespace fibrecell::daemon::jobs {

JobsConfig load_jobs_config(config::Section s) {
    JobsConfig c;
    if (s.has("state_dir"))
        s.fail("state_dir", "is the cell YAML's top-level state_dir (one folder for the whole service)");
    c.planning_workers = s.integer("planning_workers", c.planning_workers, 1, 16);
    c.planner_threads = s.integer("planner_threads", c.planner_threads, 0, 256);
    c.planner_nice = s.integer("planner_nice", c.planner_nice, 0, 19);
    c.max_queued = s.integer("max_queued", c.max_queued, 1, 10000);
    c.keep_completed = s.integer("keep_completed", c.keep_completed, 0, 100000);
    c.plan_retries = s.integer("plan_retries", c.plan_retries, 0, 10);
    c.stop_grace_s = s.number("stop_grace_s", c.stop_grace_s, 0, 25);
    s.finish();
    return c;
}

}  // namespace fibrecell::daemon::jobs
