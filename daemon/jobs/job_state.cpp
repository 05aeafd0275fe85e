#include "daemon/jobs/job_state.hpp"

namespace fibrecell::daemon::jobs {
namespace {

using S = JobState;
using A = JobAction;

struct Transition {
    S from;
    A action;
    S to;
};

// Every allowed transition; anything else is refused (user actions) or a logic error.
constexpr Transition transitions[] = {
    {S::planning, A::plan_done, S::planned},
    {S::planning, A::plan_failed, S::failed},
    {S::planning, A::abort, S::aborted},
    {S::planning, A::service_restarted, S::planning},  // re-queued (within the retry limit)
    {S::planning, A::print_failed, S::failed},         // retry limit reached

    {S::planned, A::start, S::starting},
    {S::planned, A::abort, S::aborted},
    {S::planned, A::remove, S::planned},
    {S::planned, A::replan, S::planning},

    {S::starting, A::print_started, S::printing},
    {S::starting, A::start_refused, S::planned},      // a fresh start: nothing moved
    {S::starting, A::start_refused, S::interrupted},  // a resume that could not start
    {S::starting, A::abort, S::aborted},
    {S::starting, A::print_failed, S::failed},
    {S::starting, A::service_restarted, S::interrupted},

    {S::printing, A::pause, S::pausing},
    {S::printing, A::faulted, S::paused},
    {S::printing, A::print_done, S::completed},
    {S::printing, A::print_short, S::completed_with_warnings},
    {S::printing, A::abort, S::aborted},
    {S::printing, A::print_failed, S::failed},
    {S::printing, A::service_restarted, S::interrupted},

    {S::pausing, A::pause_done, S::paused},
    // A pause asked for as the last move ends: the part is printed, so the job completes.
    {S::pausing, A::print_done, S::completed},
    {S::pausing, A::print_short, S::completed_with_warnings},
    {S::pausing, A::faulted, S::paused},
    {S::pausing, A::abort, S::aborted},
    {S::pausing, A::print_failed, S::failed},
    {S::pausing, A::service_restarted, S::interrupted},

    {S::paused, A::resume, S::printing},
    {S::paused, A::print_done, S::completed},  // the pause took hold after the last move (above)
    {S::paused, A::print_short, S::completed_with_warnings},
    {S::paused, A::abort, S::aborted},
    {S::paused, A::print_failed, S::failed},
    {S::paused, A::service_restarted, S::interrupted},

    {S::interrupted, A::resume, S::starting},
    {S::interrupted, A::abort, S::aborted},

    {S::completed, A::remove, S::completed},
    {S::completed_with_warnings, A::remove, S::completed_with_warnings},
    {S::aborted, A::remove, S::aborted},
    {S::failed, A::remove, S::failed},
    {S::failed, A::replan, S::planning},
};

// What to tell the user for a forbidden action: what the job needs first.
std::string hint(S state, A action) {
    switch (state) {
        case S::planning:
            if (action == A::start) return "it can start once it is planned";
            if (action == A::remove) return "abort it first";
            if (action == A::replan) return "it is planning already";
            return "nothing is printing";
        case S::planned:
            if (action == A::resume) return "it has not started: start it";
            return "it is not printing";
        case S::starting:
            if (action == A::start) return "it is starting already";
            if (action == A::replan) return "its print has started: abort it first";
            if (action == A::remove) return "abort it first";
            return "wait until it prints, or abort it";
        case S::printing:
            if (action == A::start) return "it is printing already";
            if (action == A::resume) return "it is not paused";
            if (action == A::replan) return "its print has started: abort it first";
            return "pause or abort it first";  // remove
        case S::pausing:
            if (action == A::pause) return "it is pausing already";
            if (action == A::replan) return "its print has started: abort it first";
            if (action == A::remove) return "abort it first";
            return "wait until it is paused, then resume it";
        case S::paused:
            if (action == A::start) return "resume it instead";
            if (action == A::pause) return "it is paused already";
            if (action == A::replan) return "its print has started: abort it first";
            return "abort it first";  // remove
        case S::interrupted:
            if (action == A::start) return "resume or abort it";
            if (action == A::pause) return "it is not printing: resume or abort it";
            if (action == A::replan)
                return "its print has started: resume it with the plan it started with, or abort it";
            return "resume or abort it first";  // remove
        case S::completed:
        case S::completed_with_warnings:
        case S::aborted:
        case S::failed:
            if (action == A::abort) return "it has ended already";
            return "it has ended: submit it again to print another";
    }
    return "not allowed";
}

}  // namespace

std::string_view to_string(JobState s) {
    switch (s) {
        case S::planning:
            return "planning";
        case S::planned:
            return "planned";
        case S::starting:
            return "starting";
        case S::printing:
            return "printing";
        case S::pausing:
            return "pausing";
        case S::paused:
            return "paused";
        case S::completed:
            return "completed";
        case S::completed_with_warnings:
            return "completed_with_warnings";
        case S::aborted:
            return "aborted";
        case S::failed:
            return "failed";
        case S::interrupted:
            return "interrupted";
    }
    return "?";
}

std::string_view to_string(JobAction a) {
    switch (a) {
        case A::start:
            return "start";
        case A::pause:
            return "pause";
        case A::resume:
            return "resume";
        case A::abort:
            return "abort";
        case A::remove:
            return "remove";
        case A::replan:
            return "replan";
        case A::plan_done:
            return "plan_done";
        case A::plan_failed:
            return "plan_failed";
        case A::print_started:
            return "print_started";
        case A::start_refused:
            return "start_refused";
        case A::pause_done:
            return "pause_done";
        case A::faulted:
            return "faulted";
        case A::print_done:
            return "print_done";
        case A::print_short:
            return "print_short";
        case A::print_failed:
            return "print_failed";
        case A::service_restarted:
            return "service_restarted";
    }
    return "?";
}

JobState parse_job_state(std::string_view word) {
    for (S s : all_job_states)
        if (to_string(s) == word) return s;
    throw std::invalid_argument("unknown job state '" + std::string(word) + "'");
}

bool is_user_action(JobAction a) {
    for (A u : user_actions)
        if (u == a) return true;
    return false;
}

bool is_ended(JobState s) {
    return s == S::completed || s == S::completed_with_warnings || s == S::aborted ||
           s == S::failed;
}

bool keeps_its_reason(JobState s) {
    return s == S::pausing || s == S::paused || s == S::aborted || s == S::failed ||
           s == S::interrupted;
}

bool holds_cell(JobState s) {
    return s == S::starting || s == S::printing || s == S::pausing || s == S::paused ||
           s == S::interrupted;
}

std::vector<JobState> allowed_targets(JobState from, JobAction action) {
    std::vector<JobState> to;
    for (const Transition& t : transitions)
        if (t.from == from && t.action == action) to.push_back(t.to);
    return to;
}

std::string refusal(long long job_id, JobState state, JobAction action) {
    if (!allowed_targets(state, action).empty()) return {};
    return "job " + std::to_string(job_id) + " is " + std::string(to_string(state)) + ": " +
           hint(state, action);
}

}  // namespace fibrecell::daemon::jobs
