#pragma once
// A libmodbus error as the operator reads it: a lost connection, a device that does not answer in
// time, or one that refuses the request (a Modbus exception), with the endpoint and the request.

#include <chrono>
#include <string>

namespace fibrecell::drivers::abb {

// `err`: errno after a failed libmodbus call; `what`: the request ("read of the inputs").
std::string modbus_error_text(int err, const std::string& endpoint, const std::string& what,
                              std::chrono::milliseconds response_timeout);

}  // namespace fibrecell::drivers::abb
