#include "daemon/print/print_file.hpp"

#include <stdexcept>

namespace fibrecell::daemon::print {

using nlohmann::json;

ChunkEntry chunk_entry(const drivers::abb::RapidModule& m) {
    return {"rapid/" + m.file_name, m.first_move, m.end_move, m.first_event, m.last_event, m.lines};
}

std::string print_json_text(const PrintFile& f) {
    json chunks = json::array();
    for (const ChunkEntry& c : f.chunks)
        chunks.push_back({{"file", c.file},
                          {"first_move", c.first_move},
                          {"end_move", c.end_move},
                          {"first_event", c.first_event},
                          {"last_event", c.last_event},
                          {"lines", c.lines}});
    const json j = {{"format", print_format},  {"job", f.job},
                    {"strategy", f.strategy},  {"layers", f.layers},
                    {"settings", to_json(f.settings)}, {"board", f.board},
                    {"chunks", chunks}};
    return j.dump(2) + "\n";
}

PrintFile parse_print_json(std::string_view text, const std::string& origin) {
    const json j = json::parse(text, nullptr, false);
    if (j.is_discarded() || !j.is_object())
        throw std::invalid_argument(origin + ": not a JSON object");
    if (j.value("format", "") != print_format)
        throw std::invalid_argument(origin + ": format is not " + std::string(print_format));
    PrintFile f;
    try {
        f.job = j.value("job", "");
        f.strategy = j.value("strategy", "");
        f.layers = j.at("layers").get<std::size_t>();
        f.settings = settings_from_json(j.at("settings"));
        f.board = j.value("board", json::object());
        for (const json& c : j.at("chunks")) {
            ChunkEntry e;
            e.file = c.at("file").get<std::string>();
            e.first_move = c.at("first_move").get<std::size_t>();
            e.end_move = c.at("end_move").get<std::size_t>();
            e.first_event = c.at("first_event").get<int>();
            e.last_event = c.at("last_event").get<int>();
            e.lines = c.at("lines").get<std::size_t>();
            if (e.end_move < e.first_move)
                throw std::invalid_argument(e.file + ": end_move before first_move");
            f.chunks.push_back(std::move(e));
        }
    } catch (const json::exception& e) {
        throw std::invalid_argument(origin + ": " + e.what());
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(origin + ": " + e.what());
    }
    return f;
}

}  // namespace fibrecell::daemon::print
