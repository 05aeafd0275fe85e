#pragma once
// Owning a directory: the service's state and socket directories must be its own, and one service
// at a time may use a state directory.
//
//   ensure_private_directory(state_dir, "state directory");  // created 0750, or checked
//   DirectoryLock lock(state_dir, "fibrecelld pid 42, socket /run/fibrecelld/api.sock");
//
// A directory is private when it is owned by this user or root and nobody but its owner may
// write to it (or it has the sticky bit, as /tmp): the same rule OpenSSH applies to the paths of
// its keys. Anything else could be a local user's trap (a pre-created /tmp/fibrecelld-sim with
// mode 0777, a socket swapped for an impostor's), so the service refuses to start on it.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace fibrecell::config {

class DirectoryRefused : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Creates `dir` (and missing parents) with mode 0750, or checks that an existing one is private;
// throws DirectoryRefused naming `what`, the path, its owner and mode, and what to do.
void ensure_private_directory(const std::filesystem::path& dir, std::string_view what);

// The same check of an existing directory, without creating it.
void check_private_directory(const std::filesystem::path& dir, std::string_view what);

// An exclusive lock on <dir>/fibrecelld.lock for the object's life; the kernel drops it when the
// process ends, kill -9 included, so a stale lock file never blocks a restart. The file holds
// `holder` (who has the lock) for the message a second taker gets: DirectoryRefused "... is in
// use by <holder>".
class DirectoryLock {
  public:
    DirectoryLock(const std::filesystem::path& dir, const std::string& holder);
    ~DirectoryLock();
    DirectoryLock(const DirectoryLock&) = delete;
    DirectoryLock& operator=(const DirectoryLock&) = delete;

  private:
    int fd_ = -1;
};

}  // namespace fibrecell::config
