#pragma once
// Files that survive a crash or a power loss: a whole file replaced atomically (readers see the
// old or the new content, never a mix) and lines appended and flushed to the disk one by one.

#include <filesystem>
#include <string_view>

namespace fibrecell::daemon::jobs {

// Writes `text` to a temporary file beside `path` ("<name>.tmp-<pid>-<n>"), fsyncs it, renames
// it over `path` and fsyncs the folder. Throws std::system_error naming the path and the step.
void write_file_durably(const std::filesystem::path& path, std::string_view text);

// fsync of a folder, so that a rename or a new entry in it is on the disk.
void sync_directory(const std::filesystem::path& dir);

// True for the temporary files write_file_durably leaves behind when it is interrupted.
bool is_leftover_temp_file(const std::filesystem::path& path);

// An append-only file: each append() is one write() of a whole line, then fdatasync, so a line
// is on the disk when append() returns. A crash can only leave the last line torn.
class DurableAppender {
  public:
    // Opens (creates) `path` for appending; a new file's folder entry is synced.
    explicit DurableAppender(const std::filesystem::path& path);
    ~DurableAppender();
    DurableAppender(const DurableAppender&) = delete;
    DurableAppender& operator=(const DurableAppender&) = delete;

    // `line` without its '\n'. Throws std::system_error naming the file.
    void append(std::string_view line);

  private:
    std::filesystem::path path_;
    int fd_ = -1;
};

}  // namespace fibrecell::daemon::jobs
