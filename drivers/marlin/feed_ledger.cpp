#include "drivers/marlin/feed_ledger.hpp"

#include "drivers/marlin/marlin_line.hpp"

#include <charconv>
#include <cctype>
#include <optional>
#include <string>

namespace fibrecell::drivers::marlin {

namespace {

// The number after the parameter letter `p` (upper case), when the command has one.
std::optional<double> parameter(std::string_view command, char p) {
    // Parameters follow the command word; a letter starts each, after a blank.
    for (std::size_t i = command.find(' '); i != std::string_view::npos && i < command.size();
         i = command.find(' ', i + 1)) {
        std::size_t at = i + 1;
        while (at < command.size() && command[at] == ' ') ++at;
        if (at >= command.size()) break;
        if (std::toupper(static_cast<unsigned char>(command[at])) != p) continue;
        double v = 0;
        const char* first = command.data() + at + 1;
        const char* last = command.data() + command.size();
        if (first < last && *first == '+') ++first;
        const auto [end, ec] = std::from_chars(first, last, v);
        if (ec != std::errc() || end == first) return std::nullopt;
        return v;
    }
    return std::nullopt;
}

bool is_move(const std::string& w) { return w == "G0" || w == "G1" || w == "G2" || w == "G3"; }

}  // namespace

bool FeedLedger::counts(std::string_view command) {
    const std::string w = command_word(command);
    if (w.size() > 1 && w[0] == 'T') return true;
    if (w == "M82" || w == "M83") return true;
    return (is_move(w) || w == "G92") && parameter(command, 'E').has_value();
}

void FeedLedger::taken(std::string_view command, bool e_ran) {
    const std::string w = command_word(command);
    if (w.size() > 1 && w[0] == 'T') {
        const int t = std::atoi(w.c_str() + 1);
        if (t < 0 || t >= FeedTotals::extruders) return;
        extruder_ = t;  // Marlin keeps one E position: the change does not move it
        return;
    }
    if (w == "M82") relative_ = false;
    if (w == "M83") relative_ = true;
    const std::optional<double> e = parameter(command, 'E');
    if (!e) return;
    if (w == "G92") {
        position_ = *e;
        return;
    }
    if (!is_move(w)) return;
    const double moved = relative_ ? *e : *e - position_;
    position_ = relative_ ? position_ + *e : *e;
    if (e_ran) totals_.mm[static_cast<std::size_t>(extruder_)] += moved;
}

void FeedLedger::firmware_started() {
    extruder_ = 0;
    relative_ = false;
    position_ = 0;
}

}  // namespace fibrecell::drivers::marlin
