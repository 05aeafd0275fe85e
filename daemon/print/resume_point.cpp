#include "daemon/print/resume_point.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace fibrecell::daemon::print {
namespace {

using drivers::abb::EventKind;
using drivers::abb::MoveRole;
using drivers::abb::PrintProgram;
using drivers::abb::ProgramEvent;

bool starts_unit(EventKind k) {
    return k == EventKind::extrude_on || k == EventKind::fibre_start;
}

std::size_t approach_of(const PrintProgram& program, int layer, int path) {
    for (std::size_t i = 0; i < program.moves.size(); ++i) {
        const auto& m = program.moves[i];
        if (m.role == MoveRole::approach && m.layer == layer && m.path == path) return i;
    }
    throw std::invalid_argument("print program has no approach onto layer " +
                                std::to_string(layer) + " path " + std::to_string(path));
}

// The unit that event `e` (0-based index) belongs to, filled into `r`.
void enter_unit(const PrintProgram& program, std::size_t e, ResumePoint& r) {
    const auto& events = program.events;
    const ProgramEvent& ev = events[e];
    r.layer = ev.layer;
    r.nozzle = ev.nozzle;
    std::size_t first = e;
    if (ev.kind == EventKind::extrude_on || ev.kind == EventKind::extrude_off) {
        r.unit = ResumeUnit::pla_layer;
        // Back to the layer's first extrude_on.
        for (std::size_t i = e + 1; i-- > 0;) {
            if (events[i].layer != ev.layer) break;
            if (events[i].kind == EventKind::extrude_on) first = i;
        }
        // Paths of the layer finished before the interruption: done, not fed again.
        for (std::size_t i = first; i < events.size() && events[i].layer == ev.layer; ++i) {
            if (events[i].kind != EventKind::extrude_off) continue;
            if (events[i].sequence > r.last_confirmed) break;
            for (std::size_t k = first; k <= i; ++k)
                if (events[k].path == events[i].path && (events[k].kind == EventKind::extrude_on ||
                                                         events[k].kind == EventKind::extrude_off))
                    r.done_in_unit.push_back(events[k].sequence);
        }
        std::sort(r.done_in_unit.begin(), r.done_in_unit.end());
    } else {
        r.unit = ResumeUnit::fibre_path;
        while (first > 0 && events[first].kind != EventKind::fibre_start) --first;
    }
    r.path = events[first].path;
    r.first_event = events[first].sequence;
    r.first_move = approach_of(program, r.layer, r.path);
    for (std::int64_t s = r.first_event; s <= r.last_confirmed; ++s)
        if (!std::binary_search(r.done_in_unit.begin(), r.done_in_unit.end(), s))
            r.fed_again.push_back(s);
}

// The first event of the unit after the one starting at index `from`; events.size() if none.
std::size_t next_unit(const PrintProgram& program, std::size_t from) {
    std::size_t i = from + 1;
    while (i < program.events.size() && !starts_unit(program.events[i].kind)) ++i;
    return i;
}

}  // namespace

bool ResumePoint::done(std::int64_t sequence) const {
    if (nothing_left) return true;
    return sequence < first_event ||
           std::binary_search(done_in_unit.begin(), done_in_unit.end(), sequence);
}

ResumePoint resume_point(const PrintProgram& program, std::int64_t last_confirmed,
                         std::optional<FibreFed> fed) {
    const auto total = static_cast<std::int64_t>(program.events.size());
    if (last_confirmed < 0 || last_confirmed > total)
        throw std::invalid_argument("last confirmed event " + std::to_string(last_confirmed) +
                                    " is outside the program's events 0.." + std::to_string(total));
    ResumePoint r;
    r.last_confirmed = last_confirmed;
    // The first event not confirmed (0-based index = its sequence - 1).
    std::size_t next = static_cast<std::size_t>(last_confirmed);
    if (next < program.events.size()) {
        const EventKind k = program.events[next].kind;
        const bool inside_unit =
            k == EventKind::extrude_off || k == EventKind::cut || starts_unit(k);
        if (!inside_unit) {
            // Between units (head_switch, layer_end) or after a cut (path_end): the next unit.
            while (next < program.events.size() && !starts_unit(program.events[next].kind)) ++next;
        }
    }
    if (next >= program.events.size()) {
        r.nothing_left = true;
        return r;
    }
    enter_unit(program, next, r);
    if (r.unit != ResumeUnit::fibre_path || r.first_event > last_confirmed) return r;
    // The fibre was threaded and the robot went on along the path: it is in the part.
    r.cut_first = true;
    if (!fed || fed->sequence != r.first_event || !(fed->mm > 0)) return r;
    const ProgramEvent& start = program.events[static_cast<std::size_t>(r.first_event - 1)];
    if (fed->mm < start.length_mm - 1e-6) {
        r.fibre_fed_mm = fed->mm;
        return r;
    }
    // Fed up to its cut: only the cut is left of the path, made before the lift.
    const std::size_t after = next_unit(program, static_cast<std::size_t>(r.first_event - 1));
    ResumePoint rest;
    rest.last_confirmed = last_confirmed;
    rest.cut_first = true;
    if (after >= program.events.size())
        rest.nothing_left = true;
    else
        enter_unit(program, after, rest);
    return rest;
}

}  // namespace fibrecell::daemon::print
