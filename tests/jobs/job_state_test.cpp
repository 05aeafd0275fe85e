// The job state table, walked whole: every user action in every state is either allowed with the
// expected next state or refused with the expected message; every service event is allowed from
// exactly the states docs/jobs.md lists.
#include "daemon/jobs/job_state.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>

using namespace fibrecell::daemon::jobs;
using S = JobState;
using A = JobAction;

namespace {

// One row per state: what each user action does (a state) or the refusal's text after
// "job 12 is <state>: ".
struct Expect {
    std::optional<S> to;
    std::string refusal;
};
Expect ok(S to) {
    return {to, ""};
}
Expect no(std::string text) {
    return {std::nullopt, std::move(text)};
}

const std::map<S, std::map<A, Expect>>& user_table() {
    static const std::map<S, std::map<A, Expect>> t = {
        {S::planning,
         {{A::start, no("it can start once it is planned")},
          {A::pause, no("nothing is printing")},
          {A::resume, no("nothing is printing")},
          {A::abort, ok(S::aborted)},
          {A::remove, no("abort it first")},
          {A::replan, no("it is planning already")}}},
        {S::planned,
         {{A::start, ok(S::starting)},
          {A::pause, no("it is not printing")},
          {A::resume, no("it has not started: start it")},
          {A::abort, ok(S::aborted)},
          {A::remove, ok(S::planned)},
          {A::replan, ok(S::planning)}}},
        {S::starting,
         {{A::start, no("it is starting already")},
          {A::pause, no("wait until it prints, or abort it")},
          {A::resume, no("wait until it prints, or abort it")},
          {A::abort, ok(S::aborted)},
          {A::remove, no("abort it first")},
          {A::replan, no("its print has started: abort it first")}}},
        {S::printing,
         {{A::start, no("it is printing already")},
          {A::pause, ok(S::pausing)},
          {A::resume, no("it is not paused")},
          {A::abort, ok(S::aborted)},
          {A::remove, no("pause or abort it first")},
          {A::replan, no("its print has started: abort it first")}}},
        {S::pausing,
         {{A::start, no("wait until it is paused, then resume it")},
          {A::pause, no("it is pausing already")},
          {A::resume, no("wait until it is paused, then resume it")},
          {A::abort, ok(S::aborted)},
          {A::remove, no("abort it first")},
          {A::replan, no("its print has started: abort it first")}}},
        {S::paused,
         {{A::start, no("resume it instead")},
          {A::pause, no("it is paused already")},
          {A::resume, ok(S::printing)},
          {A::abort, ok(S::aborted)},
          {A::remove, no("abort it first")},
          {A::replan, no("its print has started: abort it first")}}},
        {S::interrupted,
         {{A::start, no("resume or abort it")},
          {A::pause, no("it is not printing: resume or abort it")},
          {A::resume, ok(S::starting)},
          {A::abort, ok(S::aborted)},
          {A::remove, no("resume or abort it first")},
          {A::replan,
           no("its print has started: resume it with the plan it started with, or abort it")}}},
    };
    return t;
}

Expect ended_expect(S s, A a) {
    if (a == A::remove) return ok(s);
    if (a == A::replan && s == S::failed) return ok(S::planning);
    if (a == A::abort) return no("it has ended already");
    return no("it has ended: submit it again to print another");
}

}  // namespace

TEST(JobStateTest, EveryUserActionInEveryStateIsAllowedOrRefusedAsTabled) {
    int allowed = 0, refused = 0;
    for (S s : all_job_states) {
        for (A a : user_actions) {
            const Expect e = is_ended(s) ? ended_expect(s, a) : user_table().at(s).at(a);
            const auto targets = allowed_targets(s, a);
            const std::string message = refusal(12, s, a);
            SCOPED_TRACE(std::string(to_string(s)) + " + " + std::string(to_string(a)));
            if (e.to) {
                ASSERT_EQ(targets.size(), 1u);
                EXPECT_EQ(targets.front(), *e.to);
                EXPECT_EQ(message, "");
                ++allowed;
            } else {
                EXPECT_TRUE(targets.empty());
                EXPECT_EQ(message, "job 12 is " + std::string(to_string(s)) + ": " + e.refusal);
                ++refused;
            }
        }
    }
    EXPECT_EQ(allowed, 18);  // 11 states x 6 actions
    EXPECT_EQ(refused, 48);
}

TEST(JobStateTest, ServiceEventsComeOnlyFromTheirStates) {
    const std::map<A, std::map<S, std::set<S>>> expected = {
        {A::plan_done, {{S::planning, {S::planned}}}},
        {A::plan_failed, {{S::planning, {S::failed}}}},
        {A::print_started, {{S::starting, {S::printing}}}},
        {A::start_refused, {{S::starting, {S::planned, S::interrupted}}}},
        {A::pause_done, {{S::pausing, {S::paused}}}},
        {A::faulted, {{S::printing, {S::paused}}, {S::pausing, {S::paused}}}},
        {A::print_done, {{S::printing, {S::completed}}, {S::pausing, {S::completed}}, {S::paused, {S::completed}}}},
        {A::print_short,
         {{S::printing, {S::completed_with_warnings}},
          {S::pausing, {S::completed_with_warnings}},
          {S::paused, {S::completed_with_warnings}}}},
        {A::print_failed,
         {{S::planning, {S::failed}},
          {S::starting, {S::failed}},
          {S::printing, {S::failed}},
          {S::pausing, {S::failed}},
          {S::paused, {S::failed}}}},
        {A::service_restarted,
         {{S::planning, {S::planning}},
          {S::starting, {S::interrupted}},
          {S::printing, {S::interrupted}},
          {S::pausing, {S::interrupted}},
          {S::paused, {S::interrupted}}}},
    };
    for (const auto& [action, from] : expected) {
        EXPECT_FALSE(is_user_action(action));
        for (S s : all_job_states) {
            const auto targets = allowed_targets(s, action);
            const std::set<S> got(targets.begin(), targets.end());
            const auto it = from.find(s);
            EXPECT_EQ(got, it == from.end() ? std::set<S>{} : it->second)
                << to_string(action) << " from " << to_string(s);
        }
    }
}

TEST(JobStateTest, NamesAreTheContractsAndRoundTrip) {
    const char* names[] = {"planning", "planned",   "starting",
                           "printing", "pausing",   "paused",
                           "completed", "completed_with_warnings", "aborted",
                           "failed",   "interrupted"};
    ASSERT_EQ(std::size(all_job_states), std::size(names));
    for (std::size_t i = 0; i < std::size(names); ++i) {
        EXPECT_EQ(to_string(all_job_states[i]), names[i]);
        EXPECT_EQ(parse_job_state(names[i]), all_job_states[i]);
    }
    EXPECT_THROW(parse_job_state("queued"), std::invalid_argument);
    for (S s : all_job_states)
        EXPECT_EQ(holds_cell(s), s == S::starting || s == S::printing || s == S::pausing ||
                                     s == S::paused || s == S::interrupted)
            << to_string(s);
}
