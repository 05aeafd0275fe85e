#pragma once
// What a method handler knows about the call besides its params.

#include <cstdint>
#include <string>

namespace fibrecell::api {

// websocket: a dashboard connection, its login checked by the HTTP listener (daemon/http).
enum class Transport { unix_socket, tcp, websocket };

struct CallContext {
    std::string method;        // "job.start"
    std::uint64_t client = 0;  // connection number, unique for the server's lifetime
    Transport transport = Transport::unix_socket;
    std::string peer;           // "unix uid=1000 pid=4242", "tcp 127.0.0.1:51234", "websocket ...": logs
    // Who is calling, for records (a job's submitter): the unix user's name ("uid 1000" when it
    // has none), "dashboard 127.0.0.1" (one token for everyone: the address tells them apart),
    // "tcp 127.0.0.1" (a token holder).
    std::string user;
    bool notification = false;  // no id: the answer is discarded
};

}  // namespace fibrecell::api
