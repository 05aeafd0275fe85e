#pragma once
// Files that survive a crash or a power loss. This is the one way the service and the planner's
// callers write files: every file is replaced atomically (a reader sees the old content or the
// new, never a mix) and is on the disk once its writer says so.
//
//   write_file_durably(job / "state.json", text);   // one file, on the disk when it returns
//
//   DurableFiles plan(dir);                         // many files, durable together:
//   plan.write("toolpaths.json", text);             //   temp + rename, writeback started
//   plan.write("rapid/FcChunk0001.mod", chunk);
//   plan.commit();                                  //   each file, then each folder fsynced

#include <filesystem>
#include <set>
#include <string_view>

namespace fibrecell::config {

// Writes `text` to a temporary file beside `path` ("<name>.tmp-<pid>-<n>", unique per writer),
// fsyncs it, renames it over `path` and fsyncs the folder. Throws std::system_error naming the
// path and the step.
void write_file_durably(const std::filesystem::path& path, std::string_view text);

// fsync of a folder, so that a rename or a new entry in it is on the disk.
void sync_directory(const std::filesystem::path& dir);

// True for the temporary files an interrupted writer leaves behind.
bool is_leftover_temp_file(const std::filesystem::path& path);

// Files under one root folder, written one by one and made durable together: each write() puts a
// complete file in place atomically (temporary name, rename; missing folders created) and starts
// its writeback, and commit() fsyncs every file written, then every folder that got a new entry,
// so that after commit() a crash or power loss keeps every file. Nothing is durable before
// commit(): a process that dies leaves complete files, but after a power loss a file written
// since the last commit may be empty or short. (A plan says it is whole with its manifest,
// written durably after the commit.)
class DurableFiles {
  public:
    explicit DurableFiles(std::filesystem::path root);

    // `relative`: below the root ("preview/layer_0001.svg"). Throws std::system_error naming the
    // file and the step.
    void write(const std::filesystem::path& relative, std::string_view text);
    // Throws std::system_error naming the folder that could not be synced.
    void commit();

    const std::filesystem::path& root() const { return root_; }

  private:
    std::filesystem::path root_;
    std::set<std::filesystem::path> written_;  // files not yet synced
    std::set<std::filesystem::path> touched_;  // folders with new entries, not yet synced
};

// An append-only file: each append() is one write() of a whole line, then fdatasync, so a line
// is on the disk when append() returns. A crash can only leave the last line torn.
class DurableAppender {
  public:
    // Opens (creates) `path` for appending; a new file's folder entry is synced.
    explicit DurableAppender(const std::filesystem::path& path);
    ~DurableAppender();
    DurableAppender(const DurableAppender&) = delete;
    DurableAppender& operator=(const DurableAppender&) = delete;

    // `line` without its '\n'. Throws std::system_error naming the file; what a failed append
    // wrote is cut off again (ENOSPC, EIO), so the file ends with a whole line.
    void append(std::string_view line);

  private:
    std::filesystem::path path_;
    int fd_ = -1;
};

}  // namespace fibrecell::config
