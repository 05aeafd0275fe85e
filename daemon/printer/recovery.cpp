#include "daemon/printer/recovery.hpp"

#include <algorithm>

namespace fibrecell::daemon::printer {

namespace {

using E = PrintEvent;
using St = Step;

// Where the event's job is with respect to the cell.
enum class Where {
    cell_free,      // nothing is on the cell
    other_on_cell,  // another job is
    printing,       // it is, printing
    held,           // it is, held (paused, or on a fault)
};

// A rule's further condition on the situation.
enum class If { always, job_ended, job_not_ended, fault_unreported };

struct Rule {
    PrintEvent event;
    Where where;
    If condition;
    std::vector<Step> steps;
    const char* refusal;  // "%" stands for the job the refusal is about; null: not refused
};

// Every event in every place; a cell with no rule does nothing. The resume of a held print is
// preceded by what recovery_steps adds.
const std::vector<Rule>& rules() {
    static const std::vector<Rule> table = {
        {E::start, Where::cell_free, If::always, {St::start_print}, nullptr},
        {E::start, Where::other_on_cell, If::always, {}, "job % is on the cell"},
        {E::start, Where::printing, If::always, {}, "job % is on the cell"},
        {E::start, Where::held, If::always, {}, "job % is on the cell"},

        {E::pause, Where::printing, If::always, {St::pause_print}, nullptr},
        {E::pause, Where::cell_free, If::job_ended, {St::note_ended}, nullptr},
        {E::pause, Where::other_on_cell, If::job_ended, {St::note_ended}, nullptr},
        {E::pause, Where::cell_free, If::job_not_ended, {}, "job % is not on the cell"},
        {E::pause, Where::other_on_cell, If::job_not_ended, {}, "job % is not on the cell"},

        {E::resume, Where::held, If::always, {St::resume_print}, nullptr},
        {E::resume, Where::cell_free, If::always, {}, "job % is not on the cell"},
        {E::resume, Where::other_on_cell, If::always, {}, "job % is not on the cell"},

        {E::abort, Where::printing, If::always, {St::abort_print}, nullptr},
        {E::abort, Where::held, If::always, {St::abort_print}, nullptr},

        {E::fault, Where::printing, If::always, {St::hold}, nullptr},
        {E::fault, Where::held, If::fault_unreported, {St::hold}, nullptr},

        // A pause that took hold after the last move: the part is printed.
        {E::completed, Where::printing, If::always, {St::finish}, nullptr},
        {E::completed, Where::held, If::always, {St::finish}, nullptr},
    };
    return table;
}

// A held print's way back, before its resume: a board that fell out is opened again and, having
// restarted, heated and given its tool again; heaters that went off while it waited are heated.
struct Recovery {
    bool Situation::*when;
    std::vector<Step> steps;
};
const std::vector<Recovery>& recovery_steps() {
    static const std::vector<Recovery> table = {
        {&Situation::board_down, {St::reconnect_board, St::reheat, St::reselect_tool}},
        {&Situation::heaters_off, {St::reheat}},
        {&Situation::tool_lost, {St::reselect_tool}},
    };
    return table;
}

Where where(std::int64_t job, const Situation& s) {
    if (s.on_cell == OnCell::nothing) return Where::cell_free;
    if (s.job_on_cell != job) return Where::other_on_cell;
    return s.on_cell == OnCell::held ? Where::held : Where::printing;
}

bool holds(If condition, const Situation& s) {
    switch (condition) {
        case If::always: return true;
        case If::job_ended: return s.job_ended;
        case If::job_not_ended: return !s.job_ended;
        case If::fault_unreported: return !s.fault_reported;
    }
    return false;
}

}  // namespace

Decision decide(PrintEvent event, std::int64_t job, const Situation& s) {
    const Where w = where(job, s);
    for (const Rule& rule : rules()) {
        if (rule.event != event || rule.where != w || !holds(rule.condition, s)) continue;
        Decision d;
        if (rule.refusal != nullptr) {
            d.refusal = rule.refusal;
            // A start names the job in the way, the others their own.
            const std::int64_t about = event == E::start ? s.job_on_cell.value_or(job) : job;
            d.refusal.replace(d.refusal.find('%'), 1, std::to_string(about));
            return d;
        }
        if (event == E::resume)
            for (const Recovery& r : recovery_steps())
                if (s.*r.when)
                    for (const Step step : r.steps)
                        if (std::find(d.steps.begin(), d.steps.end(), step) == d.steps.end())
                            d.steps.push_back(step);
        d.steps.insert(d.steps.end(), rule.steps.begin(), rule.steps.end());
        return d;
    }
    return {};
}

std::string_view to_string(PrintEvent event) {
    switch (event) {
        case PrintEvent::start: return "start";
        case PrintEvent::pause: return "pause";
        case PrintEvent::resume: return "resume";
        case PrintEvent::abort: return "abort";
        case PrintEvent::fault: return "fault";
        case PrintEvent::completed: return "completed";
    }
    return "?";
}

std::string_view to_string(Step step) {
    switch (step) {
        case Step::start_print: return "start_print";
        case Step::pause_print: return "pause_print";
        case Step::note_ended: return "note_ended";
        case Step::reconnect_board: return "reconnect_board";
        case Step::reheat: return "reheat";
        case Step::reselect_tool: return "reselect_tool";
        case Step::resume_print: return "resume_print";
        case Step::abort_print: return "abort_print";
        case Step::hold: return "hold";
        case Step::finish: return "finish";
    }
    return "?";
}

}  // namespace fibrecell::daemon::printer
