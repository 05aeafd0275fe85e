#include "daemon/history/history_file.hpp"

#include "config/durable_file.hpp"

#include <fstream>

namespace fibrecell::daemon::history {

HistoryRead read_history(const std::filesystem::path& file) {
    HistoryRead out;
    std::ifstream in(file);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        if (line.empty()) continue;
        try {
            out.records.push_back(history_record_from_json(nlohmann::json::parse(line)));
        } catch (const std::exception& e) {
            out.skipped.push_back(file.filename().string() + " line " + std::to_string(number) +
                                  ": " + e.what());
        }
    }
    return out;
}

void write_history(const std::filesystem::path& file, const std::vector<HistoryRecord>& records) {
    std::string text;
    for (const HistoryRecord& r : records) text += to_json(r).dump() + "\n";
    config::write_file_durably(file, text);
}

}  // namespace fibrecell::daemon::history
