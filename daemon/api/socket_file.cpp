#include "daemon/api/socket_file.hpp"

#include "config/directory_owner.hpp"
#include "daemon/api/api_server.hpp"

#include <grp.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace fibrecell::api {

namespace {

std::string errno_text(int err) {
    return std::strerror(err);
}

// True when a process accepts connections on the socket file at `path`.
bool socket_is_live(const std::string& path) {
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) throw ApiStartError("cannot create a Unix socket: " + errno_text(errno));
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::memcpy(addr.sun_path, path.c_str(), path.size() + 1);
    const int rc = ::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr);
    const int err = errno;
    ::close(fd);
    if (rc == 0) return true;
    if (err == ECONNREFUSED) return false;  // nobody listens: left behind by a dead process
    // EAGAIN: a live listener with a full backlog; anything else we cannot judge.
    if (err == EAGAIN) return true;
    throw ApiStartError("cannot check the existing socket " + path + ": " + errno_text(err));
}

}  // namespace

void prepare_socket_path(const std::string& path) {
    if (path.size() >= sizeof(sockaddr_un{}.sun_path))
        throw ApiStartError("socket path is too long (" + std::to_string(path.size()) +
                            " bytes, at most " +
                            std::to_string(sizeof(sockaddr_un{}.sun_path) - 1) + "): " + path);
    const auto dir = std::filesystem::path(path).parent_path();
    std::error_code fs_ec;
    if (!dir.empty() && !std::filesystem::is_directory(dir, fs_ec))
        throw ApiStartError("cannot create socket " + path + ": directory " + dir.string() +
                            " does not exist");
    // Whoever may write to the directory may swap the socket for their own server.
    if (!dir.empty()) {
        try {
            config::check_private_directory(dir, "socket directory");
        } catch (const config::DirectoryRefused& e) {
            throw ApiStartError(e.what());
        }
    }
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) {
        if (errno == ENOENT) return;
        throw ApiStartError("cannot inspect " + path + ": " + errno_text(errno));
    }
    if (!S_ISSOCK(st.st_mode))
        throw ApiStartError(path + " exists and is not a socket; remove it or choose another path");
    if (socket_is_live(path)) throw ApiStartError("another fibrecelld is listening on " + path);
    if (::unlink(path.c_str()) != 0 && errno != ENOENT)
        throw ApiStartError("cannot remove the stale socket " + path + ": " + errno_text(errno));
}

void apply_socket_permissions(const std::string& path, unsigned mode,
                              const std::string& group_name) {
    if (!group_name.empty()) {
        gid_t gid = 0;
        if (group_name.find_first_not_of("0123456789") == std::string::npos) {
            gid = static_cast<gid_t>(std::stoul(group_name));
        } else {
            const struct group* g = ::getgrnam(group_name.c_str());
            if (!g)
                throw ApiStartError("api.socket_group: no group '" + group_name +
                                    "' on this system");
            gid = g->gr_gid;
        }
        if (::chown(path.c_str(), static_cast<uid_t>(-1), gid) != 0)
            throw ApiStartError("cannot give " + path + " to group " + group_name + ": " +
                                errno_text(errno));
    }
    if (::chmod(path.c_str(), static_cast<mode_t>(mode)) != 0)
        throw ApiStartError("cannot set the mode of " + path + ": " + errno_text(errno));
}

SocketFileId identify_socket_file(const std::string& path) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) return {};
    return {st.st_dev, st.st_ino, st.st_ctim};
}

void remove_socket_file_if_ours(const std::string& path, SocketFileId id) {
    if (id.inode == 0) return;
    const SocketFileId now = identify_socket_file(path);
    if (now.device == id.device && now.inode == id.inode &&
        now.changed.tv_sec == id.changed.tv_sec && now.changed.tv_nsec == id.changed.tv_nsec)
        ::unlink(path.c_str());
}

}  // namespace fibrecell::api
