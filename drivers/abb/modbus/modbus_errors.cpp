#include "drivers/abb/modbus/modbus_errors.hpp"

#include <modbus.h>

#include <cerrno>

namespace fibrecell::drivers::abb {

std::string modbus_error_text(int err, const std::string& endpoint, const std::string& what,
                              std::chrono::milliseconds response_timeout) {
    const std::string msg = modbus_strerror(err);
    switch (err) {
        case ECONNRESET:
        case EPIPE:
        case ECONNABORTED:
        case ENOTCONN:
        case EBADF:
            return endpoint + ": connection lost (" + msg + ")";
        case ETIMEDOUT:
            return endpoint + ": no response to " + what + " within " +
                   std::to_string(response_timeout.count()) + " ms (" + msg + ")";
        default:
            break;
    }
    if (err > MODBUS_ENOBASE)
        return endpoint + ": " + what + " refused by the device (" + msg + ")";
    return endpoint + ": " + what + " failed (" + msg + ")";
}

}  // namespace fibrecell::drivers::abb
