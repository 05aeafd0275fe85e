#pragma once
// print.json of the plan directory: what the print runs besides the program — the settings made
// from the job and the cell (print_settings.hpp), the RAPID chunks in order with the moves and
// events each holds, and, for people reviewing the plan, what the board will be told.
//
//   {"format": "fibrecell.print/1", "job": "loop", "strategy": "field", "layers": 26,
//    "settings": {"pla": {"temp_c": 200, ...}, "ccf": {...}, "cutter_distance_mm": 42},
//    "board": {"pla_e_per_path_mm": 0.2661, "thread_feed_mm": 42, "pla_tool": 0, "ccf_tool": 1},
//    "chunks": [{"file": "rapid/FcChunk0001.mod", "first_move": 0, "end_move": 812,
//                "first_event": 1, "last_event": 120, "lines": 4987}, ...]}

#include "daemon/print/print_settings.hpp"
#include "drivers/abb/rapid/rapid_writer.hpp"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::daemon::print {

inline constexpr std::string_view print_format = "fibrecell.print/1";

struct ChunkEntry {
    std::string file;  // "rapid/FcChunk0001.mod"
    std::size_t first_move = 0, end_move = 0;  // program moves [first_move, end_move)
    int first_event = 0, last_event = 0;       // 0 when the chunk has none
    std::size_t lines = 0;
};

struct PrintFile {
    std::string job;
    std::string strategy;
    std::size_t layers = 0;
    PrintSettings settings;
    nlohmann::json board = nlohmann::json::object();  // for review; the print does not read it
    std::vector<ChunkEntry> chunks;
};

// "rapid/" + the module's file name, with its moves and events.
ChunkEntry chunk_entry(const drivers::abb::RapidModule& module);

std::string print_json_text(const PrintFile& f);
// Throws std::invalid_argument naming `origin` and the key.
PrintFile parse_print_json(std::string_view text, const std::string& origin);

}  // namespace fibrecell::daemon::print
