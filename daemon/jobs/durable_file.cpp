#include "daemon/jobs/durable_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <string>
#include <system_error>

namespace fibrecell::daemon::jobs {
namespace {

constexpr std::string_view temp_marker = ".tmp-";

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path) {
    throw std::system_error(errno, std::generic_category(), what + " " + path.string());
}

void write_all(int fd, std::string_view text, const std::filesystem::path& path) {
    while (!text.empty()) {
        const ssize_t n = ::write(fd, text.data(), text.size());
        if (n < 0) {
            if (errno == EINTR) continue;
            fail("cannot write", path);
        }
        text.remove_prefix(static_cast<std::size_t>(n));
    }
}

}  // namespace

void sync_directory(const std::filesystem::path& dir) {
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) fail("cannot open folder", dir);
    const int rc = ::fsync(fd);
    const int err = errno;
    ::close(fd);
    errno = err;
    if (rc != 0) fail("cannot sync folder", dir);
}

void write_file_durably(const std::filesystem::path& path, std::string_view text) {
    static std::atomic<unsigned> counter{0};
    std::filesystem::path temp = path;
    temp += std::string(temp_marker) + std::to_string(::getpid()) + "-" +
            std::to_string(counter.fetch_add(1));
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) fail("cannot create", temp);
    try {
        write_all(fd, text, temp);
        if (::fsync(fd) != 0) fail("cannot sync", temp);
    } catch (...) {
        ::close(fd);
        ::unlink(temp.c_str());
        throw;
    }
    ::close(fd);
    if (::rename(temp.c_str(), path.c_str()) != 0) {
        const int err = errno;
        ::unlink(temp.c_str());
        errno = err;
        fail("cannot rename " + temp.string() + " to", path);
    }
    const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : ".";
    sync_directory(dir);
}

bool is_leftover_temp_file(const std::filesystem::path& path) {
    return path.filename().string().find(temp_marker) != std::string::npos;
}

DurableAppender::DurableAppender(const std::filesystem::path& path) : path_(path) {
    const bool existed = std::filesystem::exists(path);
    fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd_ < 0) fail("cannot open", path);
    if (!existed) sync_directory(path.has_parent_path() ? path.parent_path() : ".");
}

DurableAppender::~DurableAppender() {
    if (fd_ >= 0) ::close(fd_);
}

void DurableAppender::append(std::string_view line) {
    std::string whole(line);
    whole += '\n';
    write_all(fd_, whole, path_);  // O_APPEND: one write() lands as one piece at the end
    if (::fdatasync(fd_) != 0) fail("cannot sync", path_);
}

}  // namespace fibrecell::daemon::jobs
