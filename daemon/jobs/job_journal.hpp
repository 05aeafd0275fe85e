#pragma once
// journal.jsonl of a job folder: an append-only record of the print's events, one JSON object per
// line, each on the disk (fdatasync) before append returns.
//
//   {"seq":57,"kind":"cut","layer":3,"path":2,"phase":"sending"}    before its commands go out
//   {"seq":57,"kind":"cut","layer":3,"path":2,"phase":"confirmed"}  the board acknowledged them
//   {"phase":"resume","first_event":41}                             a resumed run re-enters here
//   {"seq":58,"phase":"fed","mm":63.0}  fibre the board took along the fibre path of fibre_start 58
//
// The service writes `sending` BEFORE it sends an extruder action, so after a crash an event that
// may have reached the board is known; `confirmed` after the sync engine's on_event_done. The last
// confirmed event (the highest, over all runs) is where resume_point() starts from. `fed` records
// follow a fibre path's feed as the board answers it (the print runner writes the latest every
// poll, off the sync engine's thread); the last one says where a re-entry lays the rest from.

#include "drivers/abb/program/print_program.hpp"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>

namespace fibrecell::config {
class DurableAppender;
}

namespace fibrecell::daemon::jobs {

struct JournalEvent {
    std::int64_t sequence = 0;  // 1-based event number of the print program
    drivers::abb::EventKind kind = drivers::abb::EventKind::layer_end;
    int layer = -1;
    int path = -1;
};

// The last `fed` record: `mm` of fibre fed along the path of fibre_start `sequence`.
struct JournalFed {
    std::int64_t sequence = 0;
    double mm = 0;
};

struct JournalSummary {
    std::int64_t last_sent = 0;       // highest `sending` sequence (0: none)
    std::int64_t last_confirmed = 0;  // highest `confirmed` sequence (0: none)
    std::optional<JournalFed> fed;    // the last `fed` record
    std::size_t records = 0;          // complete lines read
    bool torn_tail = false;           // the last line was cut short by a crash (ignored)
};

class JournalError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Reads a journal; a missing file is an empty journal. A torn last line (no '\n', or not JSON) is
// ignored and reported; any other bad line throws JournalError naming the file and line.
JournalSummary read_journal(const std::filesystem::path& path);

// Cuts a torn last line off, so that the next record starts on a line of its own.
void repair_journal(const std::filesystem::path& path);

class JobJournal {
  public:
    // Opens (creates) the journal for appending; `summary` is what read_journal found in it.
    JobJournal(const std::filesystem::path& path, const JournalSummary& summary = {});
    ~JobJournal();

    // Each returns once the record is on the disk. Thread-safe. Throws std::system_error.
    void sending(const JournalEvent& e);
    void confirmed(const JournalEvent& e);
    void resumed(std::int64_t first_event);
    void fed(const JournalFed& f);

    std::int64_t last_sent() const;
    std::int64_t last_confirmed() const;
    std::optional<JournalFed> last_fed() const;

  private:
    mutable std::mutex mu_;
    std::unique_ptr<config::DurableAppender> file_;
    JournalSummary summary_;
};

}  // namespace fibrecell::daemon::jobs
