#include "drivers/marlin/marlin_reply.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>

namespace fibrecell::drivers::marlin {
namespace {

bool starts_with_ci(std::string_view s, std::string_view prefix) {
    if (s.size() < prefix.size()) return false;
    for (std::size_t i = 0; i < prefix.size(); ++i) {
        if (std::tolower(static_cast<unsigned char>(s[i])) !=
            std::tolower(static_cast<unsigned char>(prefix[i])))
            return false;
    }
    return true;
}

bool contains_ci(std::string_view s, std::string_view needle) {
    auto it = std::search(s.begin(), s.end(), needle.begin(), needle.end(), [](char a, char b) {
        return std::tolower(static_cast<unsigned char>(a)) ==
               std::tolower(static_cast<unsigned char>(b));
    });
    return it != s.end();
}

std::string_view ltrim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    return s;
}

// The first integer in `s` after an optional "N" / "N:" (resend spellings vary by firmware).
std::optional<std::int64_t> first_number(std::string_view s) {
    std::size_t i = 0;
    while (i < s.size() && !std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
    if (i == s.size()) return std::nullopt;
    std::int64_t v = 0;
    auto [p, ec] = std::from_chars(s.data() + i, s.data() + s.size(), v);
    if (ec != std::errc()) return std::nullopt;
    return v;
}

std::optional<double> number_at(std::string_view s, std::size_t& i) {
    while (i < s.size() && s[i] == ' ') ++i;
    const char* begin = s.data() + i;
    char* end = nullptr;
    std::string tmp(begin, s.size() - i);
    const double v = std::strtod(tmp.c_str(), &end);
    if (end == tmp.c_str()) return std::nullopt;
    i += static_cast<std::size_t>(end - tmp.c_str());
    return v;
}

// "ok N12 P15 B3": the ADVANCED_OK fields.
void parse_ok_fields(std::string_view rest, Reply& r) {
    std::size_t i = 0;
    while (i < rest.size()) {
        while (i < rest.size() && rest[i] == ' ') ++i;
        if (i + 1 >= rest.size()) break;
        const char key = rest[i];
        if ((key == 'N' || key == 'P' || key == 'B') &&
            std::isdigit(static_cast<unsigned char>(rest[i + 1]))) {
            std::int64_t v = 0;
            auto [p, ec] = std::from_chars(rest.data() + i + 1, rest.data() + rest.size(), v);
            if (ec != std::errc()) break;
            if (key == 'N') r.line = v;
            if (key == 'P') r.planner_free = static_cast<int>(v);
            if (key == 'B') r.buffer_free = static_cast<int>(v);
            i = static_cast<std::size_t>(p - rest.data());
        } else {
            while (i < rest.size() && rest[i] != ' ') ++i;
        }
    }
}

bool is_fatal_error(std::string_view text) {
    for (std::string_view word : {"kill() called", "Printer halted", "Thermal Runaway",
                                  "Thermal Malfunction", "MAXTEMP", "MINTEMP", "Heating failed",
                                  "Printer stopped", "Watchdog barked", "KILL caused"}) {
        if (contains_ci(text, word)) return true;
    }
    return false;
}

}  // namespace

const TemperatureReading* TemperatureReport::find(std::string_view sensor) const {
    for (const auto& r : readings) {
        if (r.sensor == sensor) return &r;
    }
    return nullptr;
}

std::optional<TemperatureReport> parse_temperatures(std::string_view text) {
    TemperatureReport rep;
    std::size_t i = 0;
    while (i < text.size()) {
        while (i < text.size() && text[i] == ' ') ++i;
        const std::size_t key_begin = i;
        while (i < text.size() && text[i] != ':' && text[i] != ' ') ++i;
        if (i >= text.size() || text[i] != ':') continue;
        const std::string key(text.substr(key_begin, i - key_begin));
        ++i;
        if (key == "W") {
            std::size_t j = i;
            if (auto v = number_at(text, j)) rep.wait_left_s = *v;
            while (i < text.size() && text[i] != ' ') ++i;
            continue;
        }
        const bool sensor = !key.empty() && (key[0] == 'T' || key[0] == 'B' || key[0] == 'C') &&
                            key.find('@') == std::string::npos &&
                            std::all_of(key.begin() + 1, key.end(), [](char c) {
                                return std::isdigit(static_cast<unsigned char>(c));
                            });
        std::size_t j = i;
        auto actual = number_at(text, j);
        if (!sensor || !actual) {
            while (i < text.size() && text[i] != ' ') ++i;
            continue;
        }
        TemperatureReading reading{key, *actual, std::nullopt};
        i = j;
        std::size_t k = i;
        while (k < text.size() && text[k] == ' ') ++k;
        if (k < text.size() && text[k] == '/') {
            ++k;
            if (auto target = number_at(text, k)) {
                reading.target_c = *target;
                i = k;
            }
        }
        rep.readings.push_back(std::move(reading));
    }
    if (rep.readings.empty()) return std::nullopt;
    return rep;
}

Reply parse_reply(std::string_view raw) {
    Reply r;
    r.text.reserve(raw.size());
    // Only printable ASCII: a reset sends line noise (NULs, 0xFF) before `start`.
    for (char c : raw) {
        const auto u = static_cast<unsigned char>(c);
        if ((u >= 0x20 && u < 0x7f) || c == '\t') r.text.push_back(c);
    }
    const std::string_view t = ltrim(r.text);
    if (t.empty()) {
        r.kind = ReplyKind::empty;
        return r;
    }
    // A reset cuts the line the firmware was sending, and the rest of it never comes: the new
    // firmware's `start` ends that line (seen in simavr with a reset mid-transmission, as on a real
    // board). A host action ("//action:start") is not a boot.
    constexpr std::string_view boot = "start";
    if (t.size() >= boot.size() && t.substr(t.size() - boot.size()) == boot &&
        !starts_with_ci(t, "//action:")) {
        r.kind = ReplyKind::start;
        r.cut_line = std::string(t.substr(0, t.size() - boot.size()));
        return r;
    }
    if (t == "ok" || starts_with_ci(t, "ok ")) {
        r.kind = ReplyKind::ok;
        const std::string_view rest = t.substr(2);
        if (rest.find("T:") != std::string_view::npos) {
            r.temperatures = parse_temperatures(rest);
        } else {
            parse_ok_fields(rest, r);
        }
        return r;
    }
    if (starts_with_ci(t, "resend:") || starts_with_ci(t, "rs ")) {
        r.kind = ReplyKind::resend;
        r.line = first_number(starts_with_ci(t, "resend:") ? t.substr(7) : t.substr(2));
        return r;
    }
    if (t == "wait") {
        r.kind = ReplyKind::wait;
        return r;
    }
    if (starts_with_ci(t, "echo:busy:") || starts_with_ci(t, "busy:")) {
        r.kind = ReplyKind::busy;
        return r;
    }
    if (starts_with_ci(t, "//action:")) {
        r.kind = ReplyKind::action;
        r.capability = std::string(t.substr(9));
        return r;
    }
    if (starts_with_ci(t, "Cap:")) {
        r.kind = ReplyKind::capability;
        const std::string_view rest = t.substr(4);
        const auto colon = rest.rfind(':');
        r.capability = std::string(rest.substr(0, colon));
        r.capability_on = colon != std::string_view::npos && rest.substr(colon + 1) == "1";
        return r;
    }
    if (starts_with_ci(t, "FIRMWARE_NAME:")) {
        r.kind = ReplyKind::firmware_info;
        return r;
    }
    if (starts_with_ci(t, "Error:") || starts_with_ci(t, "!!")) {
        const bool line_error = contains_ci(t, "Line Number") || contains_ci(t, "checksum") ||
                                contains_ci(t, "expected line") || contains_ci(t, "format error");
        if (line_error && !is_fatal_error(t)) {
            r.kind = ReplyKind::line_error;
            const auto last = t.rfind("Last Line:");
            if (last != std::string_view::npos) r.line = first_number(t.substr(last));
        } else {
            r.kind = ReplyKind::error;
            r.fatal = is_fatal_error(t);
        }
        return r;
    }
    if (starts_with_ci(t, "echo:")) {
        r.kind = ReplyKind::echo;
        return r;
    }
    if ((t.size() > 2 && (t[0] == 'T' || t[0] == 'B') && t.find(':') != std::string_view::npos)) {
        if ((r.temperatures = parse_temperatures(t))) {
            r.kind = ReplyKind::temperature;
            return r;
        }
    }
    r.kind = ReplyKind::other;
    return r;
}

std::string_view to_string(ReplyKind k) {
    switch (k) {
        case ReplyKind::empty: return "empty";
        case ReplyKind::ok: return "ok";
        case ReplyKind::resend: return "resend";
        case ReplyKind::busy: return "busy";
        case ReplyKind::wait: return "wait";
        case ReplyKind::line_error: return "line_error";
        case ReplyKind::error: return "error";
        case ReplyKind::echo: return "echo";
        case ReplyKind::temperature: return "temperature";
        case ReplyKind::start: return "start";
        case ReplyKind::action: return "action";
        case ReplyKind::capability: return "capability";
        case ReplyKind::firmware_info: return "firmware_info";
        case ReplyKind::other: return "other";
    }
    return "?";
}

}  // namespace fibrecell::drivers::marlin
