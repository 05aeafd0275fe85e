#pragma once
// journal.jsonl of a job folder: an append-only record of the print's events, one JSON object per
// line, each on the disk (fdatasync) before append returns.
//
//   {"seq":57,"kind":"cut","layer":3,"path":2,"phase":"sending"}    before its commands go out
//   {"seq":57,"kind":"cut","layer":3,"path":2,"phase":"confirmed"}  the board acknowledged them
//   {"phase":"resume","first_event":41}                             a resumed run re-enters here
//   {"seq":58,"phase":"fed","mm":63.0}  fibre the board took along the fibre path of fibre_start 58
//   {"phase":"used","pla_mm":812.4,"fibre_mm":1520.0}  filament the board took for the job, all runs
//
// The service writes `sending` BEFORE it sends an extruder action, so after a crash an event that
// may have reached the board is known; `confirmed` after the sync engine's on_event_done. The last
// confirmed event (the highest, over all runs) is where resume_point() starts from. `fed` records
// follow a fibre path's feed as the board answers it (the print runner writes the latest every
// poll, off the sync engine's thread); the last one says where a re-entry lays the rest from.
// `used` records follow the extruder link's feed ledger the same way (every poll it changed, and
// at the print's end): the last one is what the job took from the spools (docs/history.md).

#include "drivers/abb/program/print_program.hpp"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

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

// Filament the board took for the job over all its runs [mm]: PLA filament on the PLA hotend,
// fibre on the fibre hotend, as the extruder link's ledger counted them.
struct JournalUsed {
    double pla_mm = 0;
    double fibre_mm = 0;
    bool operator==(const JournalUsed&) const = default;
};

struct JournalSummary {
    std::int64_t last_sent = 0;       // highest `sending` sequence (0: none)
    std::int64_t last_confirmed = 0;  // highest `confirmed` sequence (0: none)
    std::optional<JournalFed> fed;    // the last `fed` record
    std::optional<JournalUsed> used;  // the last `used` record
    int layers_done = 0;              // 1 + the highest layer whose layer_end was confirmed
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

// Appends records in the order given. `confirmed` and `fed` records are queued and return at
// once: a writer thread of the journal appends what is queued and syncs once per batch, so that
// the sync engine (whose observer writes them) never waits for the disk. A crash loses at most
// the last batch, i.e. the re-entry starts a few events early; the journal's meaning is its
// highest confirmed event and its last fed record, so a lost batch leaves no hole.
class JobJournal {
  public:
    // Opens (creates) the journal for appending; `summary` is what read_journal found in it.
    JobJournal(const std::filesystem::path& path, const JournalSummary& summary = {});
    ~JobJournal();  // writes what is queued first

    // On the disk before they return. Throw std::system_error.
    void sending(const JournalEvent& e);
    void resumed(std::int64_t first_event);
    // Queued; a failed write is reported by take_failure(). Thread-safe.
    void confirmed(const JournalEvent& e);
    void fed(const JournalFed& f);
    void used(const JournalUsed& u);

    // Returns once everything queued so far is on the disk (or failed).
    void flush();
    // Why the last batch could not be written (ENOSPC, EIO), once; nothing when all went well.
    std::optional<std::string> take_failure();

    std::int64_t last_sent() const;
    std::int64_t last_confirmed() const;
    std::optional<JournalFed> last_fed() const;
    std::optional<JournalUsed> last_used() const;

  private:
    void queue(std::string line);
    void write_queued();
    void append_now(const std::string& line);

    mutable std::mutex mu_;
    std::condition_variable wake_, written_;
    std::vector<std::string> queued_;
    std::uint64_t queued_count_ = 0, written_count_ = 0;
    std::optional<std::string> failure_;
    bool stopping_ = false;
    std::mutex file_mu_;  // one append at a time: the writer's batches and the direct records
    std::unique_ptr<config::DurableAppender> file_;
    JournalSummary summary_;
    std::thread writer_;
};

}  // namespace fibrecell::daemon::jobs
