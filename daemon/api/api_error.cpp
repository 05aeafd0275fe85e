#include "daemon/api/api_error.hpp"

namespace fibrecell::api {

std::string_view error_name(int code) {
    switch (code) {
        case errc::parse_error:
            return "parse_error";
        case errc::invalid_request:
            return "invalid_request";
        case errc::method_not_found:
            return "method_not_found";
        case errc::invalid_params:
            return "invalid_params";
        case errc::internal_error:
            return "internal_error";
        case errc::unauthorized:
            return "unauthorized";
        case errc::not_found:
            return "not_found";
        case errc::conflict:
            return "conflict";
        case errc::too_large:
            return "too_large";
        case errc::unavailable:
            return "unavailable";
        default:
            return "error";
    }
}

ApiError::ApiError(int code, const std::string& message, nlohmann::json data)
    : std::runtime_error(message), code_(code), data_(std::move(data)) {}

ApiError ApiError::invalid_params(const std::string& message) {
    return {errc::invalid_params, message};
}
ApiError ApiError::unauthorized(const std::string& message) {
    return {errc::unauthorized, message};
}
ApiError ApiError::not_found(const std::string& message) {
    return {errc::not_found, message};
}
ApiError ApiError::conflict(const std::string& message) {
    return {errc::conflict, message};
}
ApiError ApiError::unavailable(const std::string& message) {
    return {errc::unavailable, message};
}
ApiError ApiError::internal(const std::string& message) {
    return {errc::internal_error, message};
}

}  // namespace fibrecell::api
