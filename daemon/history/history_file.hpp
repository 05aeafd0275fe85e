#pragma once
// <state_dir>/history.jsonl: the history's records, one JSON object a line, oldest first, replaced
// whole at every change (temp, fsync, rename), so a crash leaves the old file or the new one.

#include "daemon/history/history_record.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace fibrecell::daemon::history {

struct HistoryRead {
    std::vector<HistoryRecord> records;  // oldest first
    std::vector<std::string> skipped;    // "history.jsonl line 7: id: expected ..." (left out)
};

// A missing file is an empty history. Lines that cannot be read are skipped and named; the
// others load.
HistoryRead read_history(const std::filesystem::path& file);
// Throws std::system_error naming the file.
void write_history(const std::filesystem::path& file, const std::vector<HistoryRecord>& records);

}  // namespace fibrecell::daemon::history
