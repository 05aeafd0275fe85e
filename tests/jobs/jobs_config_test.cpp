// The `jobs:` section of the cell YAML: defaults, every key, and errors that name the key.
#include "daemon/jobs/jobs_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

using namespace fibrecell;
using namespace fibrecell::daemon::jobs;

namespace {

JobsConfig load(const std::string& yaml) {
    auto root = config::Section::load_text(yaml, "cell.yaml");
    JobsConfig c = load_jobs_config(root.section("jobs"));
    root.finish();
    return c;
}

std::string error_of(const std::string& yaml) {
    try {
        load(yaml);
    } catch (const config::ConfigError& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace

TEST(JobsConfigTest, DefaultsWithoutTheSection) {
    const JobsConfig c = load("{}\n");
    EXPECT_EQ(c.planning_workers, 1);
    EXPECT_EQ(c.planner_threads, 0);
    EXPECT_EQ(c.planner_nice, 10);
    EXPECT_EQ(c.max_queued, 16);
    EXPECT_EQ(c.keep_completed, 50);
    EXPECT_EQ(c.plan_retries, 3);
}

TEST(JobsConfigTest, ReadsEveryKey) {
    const JobsConfig c = load(
        "jobs:\n  planning_workers: 2\n  planner_threads: 4\n  planner_nice: 0\n"
        "  max_queued: 3\n  keep_completed: 0\n  plan_retries: 5\n");
    EXPECT_EQ(c.planning_workers, 2);
    EXPECT_EQ(c.planner_threads, 4);
    EXPECT_EQ(c.planner_nice, 0);
    EXPECT_EQ(c.max_queued, 3);
    EXPECT_EQ(c.keep_completed, 0);
    EXPECT_EQ(c.plan_retries, 5);
}

TEST(JobsConfigTest, ErrorsNameTheKeyAndLine) {
    using ::testing::HasSubstr;
    EXPECT_THAT(error_of("jobs:\n  planning_workers: 0\n"),
                HasSubstr("line 2: jobs.planning_workers: must be in [1, 16], got 0"));
    EXPECT_THAT(error_of("jobs:\n  max_queued: -1\n"), HasSubstr("jobs.max_queued"));
    EXPECT_THAT(error_of("jobs:\n  plan_retries: 11\n"), HasSubstr("jobs.plan_retries"));
    EXPECT_THAT(error_of("jobs:\n  planner_nice: 20\n"),
                HasSubstr("jobs.planner_nice: must be in [0, 19], got 20"));
    EXPECT_THAT(error_of("jobs:\n  state_dir: /srv/fc\n"),
                HasSubstr("jobs.state_dir: is the cell YAML's top-level state_dir"));
    EXPECT_THAT(error_of("jobs:\n  planning_worker: 2\n"), HasSubstr("jobs.planning_worker"));
    EXPECT_THAT(error_of("jobs:\n  planner_threads: many\n"), HasSubstr("jobs.planner_threads"));
}
