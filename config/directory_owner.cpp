#include "config/directory_owner.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace fibrecell::config {

namespace {

std::string octal(mode_t mode) {
    char text[8];
    std::snprintf(text, sizeof text, "%04o", static_cast<unsigned>(mode & 07777));
    return text;
}

}  // namespace

void check_private_directory(const std::filesystem::path& dir, std::string_view what) {
    struct stat st {};
    if (::stat(dir.c_str(), &st) != 0)
        throw DirectoryRefused(std::string(what) + " " + dir.string() + ": " + std::strerror(errno));
    if (!S_ISDIR(st.st_mode))
        throw DirectoryRefused(std::string(what) + " " + dir.string() + " is not a directory");
    const uid_t me = ::geteuid();
    if (st.st_uid != me && st.st_uid != 0)
        throw DirectoryRefused(std::string(what) + " " + dir.string() + " belongs to uid " +
                               std::to_string(st.st_uid) + ", not to this service's (uid " +
                               std::to_string(me) +
                               "): another user made it; remove it or use another directory");
    const bool sticky = (st.st_mode & S_ISVTX) != 0;
    if ((st.st_mode & (S_IWGRP | S_IWOTH)) != 0 && !sticky)
        throw DirectoryRefused(std::string(what) + " " + dir.string() + " has mode " +
                               octal(st.st_mode) +
                               ": others may write to it; chmod go-w it (0750) or use another "
                               "directory");
}

void ensure_private_directory(const std::filesystem::path& dir, std::string_view what) {
    std::error_code ec;
    if (!std::filesystem::exists(dir, ec)) {
        if (dir.has_parent_path()) std::filesystem::create_directories(dir.parent_path(), ec);
        if (::mkdir(dir.c_str(), 0750) != 0 && errno != EEXIST)
            throw DirectoryRefused("cannot create " + std::string(what) + " " + dir.string() +
                                   ": " + std::strerror(errno));
    }
    check_private_directory(dir, what);
}

DirectoryLock::DirectoryLock(const std::filesystem::path& dir, const std::string& holder) {
    const std::filesystem::path file = dir / "fibrecelld.lock";
    fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0640);
    if (fd_ < 0)
        throw DirectoryRefused("cannot open " + file.string() + ": " + std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
        const int error = errno;
        char text[512] = {};
        const ssize_t n = ::pread(fd_, text, sizeof text - 1, 0);
        ::close(fd_);
        fd_ = -1;
        std::string who = n > 0 ? std::string(text, static_cast<std::size_t>(n)) : "";
        while (!who.empty() && (who.back() == '\n' || who.back() == '\r')) who.pop_back();
        if (error == EWOULDBLOCK)
            throw DirectoryRefused(dir.string() + " is in use by " +
                                   (who.empty() ? std::string("another service") : who) +
                                   ": one service per state directory");
        throw DirectoryRefused("cannot lock " + file.string() + ": " + std::strerror(error));
    }
    const std::string text = holder + "\n";
    if (::ftruncate(fd_, 0) != 0 ||
        ::pwrite(fd_, text.data(), text.size(), 0) != static_cast<ssize_t>(text.size())) {
        // The lock holds without the text; a second taker is told "another service".
    }
}

DirectoryLock::~DirectoryLock() {
    if (fd_ >= 0) ::close(fd_);
}

}  // namespace fibrecell::config
