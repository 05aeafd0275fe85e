#include "drivers/abb/rws/rws_error.hpp"

namespace fibrecell::drivers::abb::rws {

std::string_view to_string(RwsErrorKind kind) {
    switch (kind) {
        case RwsErrorKind::auth:
            return "auth";
        case RwsErrorKind::mastership:
            return "mastership";
        case RwsErrorKind::build:
            return "build";
        case RwsErrorKind::not_found:
            return "not_found";
        case RwsErrorKind::state:
            return "state";
        case RwsErrorKind::transport:
            return "transport";
        case RwsErrorKind::protocol:
            return "protocol";
    }
    return "unknown";
}

}  // namespace fibrecell::drivers::abb::rws
