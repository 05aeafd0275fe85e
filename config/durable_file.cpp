#include "config/durable_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <string>
#include <system_error>

namespace fibrecell::config {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view temp_marker = ".tmp-";

[[noreturn]] void fail(const std::string& what, const fs::path& path) {
    throw std::system_error(errno, std::generic_category(), what + " " + path.string());
}

void write_all(int fd, std::string_view text, const fs::path& path) {
    while (!text.empty()) {
        const ssize_t n = ::write(fd, text.data(), text.size());
        if (n < 0) {
            if (errno == EINTR) continue;
            fail("cannot write", path);
        }
        text.remove_prefix(static_cast<std::size_t>(n));
    }
}

fs::path folder_of(const fs::path& path) {
    return path.has_parent_path() ? path.parent_path() : fs::path(".");
}

enum class Sync { now, later };

// The complete file at `path`, replaced atomically. Sync::now: its data is on the disk before the
// rename, only its folder entry is not yet durable. Sync::later: its writeback is only started,
// and the caller fsyncs it before relying on it (many files' I/O then overlaps instead of each
// write waiting for the disk in turn).
void replace_file(const fs::path& path, std::string_view text, Sync sync) {
    static std::atomic<unsigned> counter{0};
    fs::path temp = path;
    temp += std::string(temp_marker) + std::to_string(::getpid()) + "-" +
            std::to_string(counter.fetch_add(1));
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) fail("cannot create", temp);
    try {
        write_all(fd, text, temp);
        if (sync == Sync::now) {
            if (::fsync(fd) != 0) fail("cannot sync", temp);
        } else {
            // A hint only: an error here shows again in the fsync that follows.
            ::sync_file_range(fd, 0, 0, SYNC_FILE_RANGE_WRITE);
        }
    } catch (...) {
        ::close(fd);
        ::unlink(temp.c_str());
        throw;
    }
    if (::close(fd) != 0) {
        const int err = errno;
        ::unlink(temp.c_str());
        errno = err;
        fail("cannot write", temp);
    }
    if (::rename(temp.c_str(), path.c_str()) != 0) {
        const int err = errno;
        ::unlink(temp.c_str());
        errno = err;
        fail("cannot rename " + temp.string() + " to", path);
    }
}

// fsync of a file or (O_DIRECTORY) a folder by its path; `kind` names it in the error.
void sync_path(const fs::path& path, int flags, const std::string& kind) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | flags);
    if (fd < 0) fail("cannot open " + kind, path);
    const int rc = ::fsync(fd);
    const int err = errno;
    ::close(fd);
    errno = err;
    if (rc != 0) fail("cannot sync " + kind, path);
}

}  // namespace

void sync_directory(const fs::path& dir) {
    sync_path(dir, O_DIRECTORY, "folder");
}

void write_file_durably(const fs::path& path, std::string_view text) {
    replace_file(path, text, Sync::now);
    sync_directory(folder_of(path));
}

bool is_leftover_temp_file(const fs::path& path) {
    return path.filename().string().find(temp_marker) != std::string::npos;
}

DurableFiles::DurableFiles(fs::path root) : root_(std::move(root)) {}

void DurableFiles::write(const fs::path& relative, std::string_view text) {
    const fs::path path = root_ / relative;
    // Folders made here are new entries of their parents: those get synced too.
    for (fs::path dir = folder_of(path); !fs::exists(dir); dir = folder_of(dir)) {
        touched_.insert(folder_of(dir));
        if (dir == folder_of(dir)) break;
    }
    std::error_code ec;
    fs::create_directories(folder_of(path), ec);
    if (ec) throw std::system_error(ec, "cannot create folder " + folder_of(path).string());
    replace_file(path, text, Sync::later);
    written_.insert(path);
    touched_.insert(folder_of(path));
}

void DurableFiles::commit() {
    for (const fs::path& path : written_)
        sync_path(path, 0, "file");  // their writeback started long ago
    written_.clear();
    // Deepest first: a folder's own entries are on the disk before its entry in its parent.
    for (auto it = touched_.rbegin(); it != touched_.rend(); ++it) sync_directory(*it);
    touched_.clear();
}

DurableAppender::DurableAppender(const fs::path& path) : path_(path) {
    const bool existed = fs::exists(path);
    fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd_ < 0) fail("cannot open", path);
    if (!existed) sync_directory(folder_of(path));
}

DurableAppender::~DurableAppender() {
    if (fd_ >= 0) ::close(fd_);
}

void DurableAppender::append(std::string_view line) {
    std::string whole(line);
    whole += '\n';
    // A write cut short (a full disk) is taken back, so that the file never holds half a line
    // for the next append to run on from.
    const off_t before = ::lseek(fd_, 0, SEEK_END);
    try {
        write_all(fd_, whole, path_);  // O_APPEND: one write() lands as one piece at the end
        if (::fdatasync(fd_) != 0) fail("cannot sync", path_);
    } catch (...) {
        if (before >= 0 && ::ftruncate(fd_, before) == 0) ::fdatasync(fd_);
        throw;
    }
}

}  // namespace fibrecell::config
