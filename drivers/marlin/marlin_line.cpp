#include "drivers/marlin/marlin_line.hpp"

#include <cctype>

namespace fibrecell::drivers::marlin {
namespace {

std::string_view trim(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    return s;
}

}  // namespace

std::uint8_t checksum(std::string_view text) {
    std::uint8_t cs = 0;
    for (char c : text) cs ^= static_cast<std::uint8_t>(c);
    return cs;
}

std::string strip_comment(std::string_view gcode) {
    std::string out;
    out.reserve(gcode.size());
    bool in_paren = false;
    for (char c : gcode) {
        if (in_paren) {
            if (c == ')') in_paren = false;
            continue;
        }
        if (c == ';') break;
        if (c == '(') {
            in_paren = true;
            continue;
        }
        out.push_back(c);
    }
    return std::string(trim(out));
}

std::string frame_line(std::int64_t line, std::string_view command) {
    const std::string_view cmd = trim(command);
    for (char c : cmd) {
        if (c == '\n' || c == '\r' || c == '*' || c == ';' || c == '\0')
            throw LineError("G-code line '" + std::string(cmd) +
                            "' contains a newline, '*', ';' or NUL; strip comments first");
    }
    std::string body = "N";
    body += std::to_string(line);
    body += ' ';
    body += cmd;
    const std::uint8_t cs = checksum(body);
    body += '*';
    body += std::to_string(cs);
    if (body.size() > max_framed_bytes)
        throw LineError("G-code line '" + std::string(cmd) + "' is " + std::to_string(body.size()) +
                        " bytes when framed; Marlin accepts at most " +
                        std::to_string(max_framed_bytes));
    return body;
}

std::string command_word(std::string_view command) {
    const std::string_view cmd = trim(command);
    std::string word;
    for (char c : cmd) {
        if (std::isspace(static_cast<unsigned char>(c))) break;
        if (!word.empty() && !std::isdigit(static_cast<unsigned char>(c)) && c != '.') break;
        word.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
    }
    return word;
}

CommandClass classify(std::string_view command) {
    const std::string w = command_word(command);
    if (w == "M109" || w == "M190") return CommandClass::heating;
    if (w == "M400" || w == "G4" || w == "M226" || w == "G28" || w == "G29" || w == "M3" ||
        w == "M4" || w == "M5")
        return CommandClass::long_running;
    if (w == "G0" || w == "G1") return CommandClass::motion;
    return CommandClass::normal;
}

std::string_view to_string(CommandClass c) {
    switch (c) {
        case CommandClass::normal: return "normal";
        case CommandClass::motion: return "motion";
        case CommandClass::long_running: return "long_running";
        case CommandClass::heating: return "heating";
    }
    return "?";
}

bool is_emergency(std::string_view command) {
    const std::string w = command_word(command);
    return w == "M108" || w == "M112" || w == "M410";
}

}  // namespace fibrecell::drivers::marlin
