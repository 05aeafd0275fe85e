// The client's text for people: bars, durations, the jobs table, the live line of `watch` and
// the outcome line, from JSON as the service sends it (docs/service.md).
#include "tools/fibrecell/job_view.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

using namespace fibrecell::tools;
using nlohmann::json;
using ::testing::HasSubstr;
using ::testing::Not;

TEST(JobView, ProgressBarRoundsToCellsAndClamps) {
    EXPECT_EQ(progress_bar(0.5, 10), "[#####-----]");
    EXPECT_EQ(progress_bar(0.04, 10), "[----------]");
    EXPECT_EQ(progress_bar(0.06, 10), "[#---------]");
    EXPECT_EQ(progress_bar(1.7, 4), "[####]");
    EXPECT_EQ(progress_bar(-1, 4), "[----]");
    EXPECT_EQ(progress_bar(std::nan(""), 4), "[----]");
}

TEST(JobView, DurationsReadLikeAClock) {
    EXPECT_EQ(duration_text(9.4), "9s");
    EXPECT_EQ(duration_text(75), "1m15s");
    EXPECT_EQ(duration_text(3725), "1h02m05s");
    EXPECT_EQ(duration_text(-1), "?");
}

TEST(JobView, JobsTableHasOneRowPerJobWithItsProgress) {
    const json jobs = json::array(
        {{{"id", 1}, {"name", "loop"}, {"state", "completed"}},
         {{"id", 2},
          {"name", "bracket"},
          {"state", "planning"},
          {"planning", {{"stage", "slice"}, {"fraction", 0.25}}}},
         {{"id", 3},
          {"name", "beam"},
          {"state", "printing"},
          {"print", {{"layer", 12}, {"layers", 40}, {"fraction", 0.3}}}},
         {{"id", 4}, {"name", "bad"}, {"state", "failed"}, {"reason", "mesh: not closed"}}});
    const std::string t = jobs_table(jobs);
    EXPECT_THAT(t, HasSubstr("   1  loop                 completed"));
    EXPECT_THAT(t, HasSubstr("planning     slice 25%"));
    EXPECT_THAT(t, HasSubstr("printing     layer 12/40 30%"));
    EXPECT_THAT(t, HasSubstr("failed       mesh: not closed"));
    EXPECT_EQ(jobs_table(json::array()), "no jobs\n");
}

TEST(JobView, LiveLineShowsLayerBarTemperaturesTimesAndSyncError) {
    const json job = {
        {"id", 3},
        {"state", "printing"},
        {"print",
         {{"layer", 2}, {"layers", 8}, {"fraction", 0.25}, {"elapsed_s", 65}, {"eta_s", 195}}}};
    const json cell = {
        {"board",
         {{"pla_c", 199.6}, {"pla_target_c", 200}, {"ccf_c", 250.2}, {"ccf_target_c", 250}}},
        {"sync", {{"cut_error_mm", {{"median", 0.012}, {"p99", 0.0456}}}}}};
    EXPECT_EQ(live_line(job, cell),
              "printing layer 2/8 [#####---------------] 25%  PLA 200/200 C  CCF 250/250 C  "
              "1m05s ETA 3m15s  cut p99 0.046 mm");
    const json planning = {{"state", "planning"},
                           {"planning", {{"stage", "vector field"}, {"fraction", 0.5}}}};
    EXPECT_EQ(live_line(planning, json::object()), "planning [##########----------] vector field");
}

TEST(JobView, OutcomeLineSummarisesACompletedJobAndNamesAFailure) {
    const json done = {
        {"id", 3},
        {"name", "loop"},
        {"state", "completed"},
        {"plan",
         {{"layers", 8}, {"fibre_length_m", 1.234}, {"pla_length_m", 10.5}, {"modules", 3}}},
        {"result",
         {{"robot_time_s", 600},
          {"elapsed_s", 30},
          {"time_scale", 20},
          {"cut_error_mm", {{"median", 0.01}, {"p99", 0.05}}}}}};
    EXPECT_EQ(outcome_line(done),
              "job 3 (loop) completed: 8 layers, fibre 1.23 m, PLA 10.50 m, 3 RAPID modules, print "
              "time 10m00s simulated (30s real), cut position error median 0.010 mm, p99 0.050 mm");
    const json failed = {{"id", 4}, {"state", "failed"}, {"reason", "mesh: 3 open edges"}};
    EXPECT_EQ(outcome_line(failed), "job 4 failed: mesh: 3 open edges");
    EXPECT_TRUE(is_final_state("aborted"));
    EXPECT_FALSE(is_final_state("interrupted"));  // may still be resumed
}

TEST(JobView, CellDetailsLeaveOutWhatTheServiceDidNotSend) {
    const json cell = {{"name", "sim-cell"},
                       {"simulated", true},
                       {"robot", {{"io", "up"}, {"running", true}, {"event", 17}}}};
    const std::string t = cell_details(cell);
    EXPECT_THAT(t, HasSubstr("cell sim-cell (simulated)"));
    EXPECT_THAT(t, HasSubstr("robot:  I/O up, running, event 17"));
    EXPECT_THAT(t, Not(HasSubstr("board")));
}

TEST(JobView, JobDetailsShowThePredictedStiffnessWhenThePlanHasIt) {
    json job = {{"id", 5},
                {"name", "loop"},
                {"state", "planned"},
                {"plan", {{"layers", 26}, {"fibre_length_m", 58.0}, {"pla_length_m", 60.1}}}};
    EXPECT_THAT(job_details(job), Not(HasSubstr("predicted")));
    job["plan"]["stiffness_n_per_mm"] = 8051.8;
    job["plan"]["stiffness_gain"] = 1.549;
    EXPECT_THAT(job_details(job),
                HasSubstr("predicted: 8052 N/mm along the load, 1.55x the part without fibre"));
}
