#pragma once
// Internal: the Unix socket file's life. Before bind: a socket file left by a dead process is
// removed, a live one (something accepts on it) is refused. After bind: group and mode. On stop:
// the file is removed only if it is still the one we bound (a successor may have replaced it).

#include <sys/types.h>

#include <ctime>

#include <string>

namespace fibrecell::api {

// dev + inode + change time: an inode number alone may be reused by a successor's socket.
struct SocketFileId {
    dev_t device = 0;
    ino_t inode = 0;
    timespec changed{};
};

// Throws ApiStartError: "another fibrecelld is listening on <path>", "<path> exists and is not a
// socket", "api.socket: directory <dir> does not exist", path too long, ...
void prepare_socket_path(const std::string& path);

// chown to the group (name or numeric gid; "" = leave it), then chmod. Throws ApiStartError.
void apply_socket_permissions(const std::string& path, unsigned mode, const std::string& group);

SocketFileId identify_socket_file(const std::string& path);  // {0,0} when absent
void remove_socket_file_if_ours(const std::string& path, SocketFileId id);

}  // namespace fibrecell::api
