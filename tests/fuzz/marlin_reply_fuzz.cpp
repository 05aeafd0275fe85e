// Feeds the bytes, line by line, as what the GT2560 prints: to the reply parser
// (drivers/marlin/marlin_reply.hpp) and to the host protocol (marlin_protocol.hpp) with a few
// numbered lines in flight. The protocol may fail the link but must not throw, crash or trip a
// sanitizer: any of those is a finding.
#include "drivers/marlin/marlin_protocol.hpp"
#include "drivers/marlin/marlin_reply.hpp"

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string>
#include <string_view>

namespace {

namespace marlin = fibrecell::drivers::marlin;

// What a print sends: every command class, so that each of their ok deadlines is reached.
constexpr std::string_view kCommands[] = {
    "G1 X10 Y5 E0.4 F720", "M105", "M109 S200", "G28", "M400", "T1"};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    marlin::ProtocolSettings settings;
    settings.window_lines = 3;
    marlin::MarlinProtocol protocol(settings,
                                    {.write = [](std::string_view) {},
                                     .acked = [](std::int64_t) {},
                                     .failed = [](marlin::LinkFailure, const std::string&) {},
                                     .observed = [](const marlin::Reply&) {}});
    // Each received line is 0.1 s after the one before: silences longer than a timeout come from
    // inputs with many lines.
    auto now = marlin::Clock::time_point{} + std::chrono::hours(1);
    const auto step = std::chrono::milliseconds(100);
    protocol.begin_session(0, now);
    std::size_t next_command = 0;

    std::string_view rest(reinterpret_cast<const char*>(data), size);
    while (!rest.empty()) {
        const auto nl = rest.find('\n');
        const std::string_view line = rest.substr(0, nl);
        rest = nl == std::string_view::npos ? std::string_view() : rest.substr(nl + 1);

        marlin::parse_reply(line);
        marlin::parse_temperatures(line);
        now += step;
        while (!protocol.failed() && protocol.queued() < 4)
            protocol.enqueue(kCommands[next_command++ % std::size(kCommands)], now);
        protocol.on_line(line, now);
        protocol.on_tick(now);
    }
    return 0;
}
