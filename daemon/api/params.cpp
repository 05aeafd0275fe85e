#include "daemon/api/params.hpp"

#include "daemon/api/api_error.hpp"

#include <cmath>
#include <sstream>

namespace fibrecell::api {

namespace {

const nlohmann::json& empty_object() {
    static const nlohmann::json empty = nlohmann::json::object();
    return empty;
}

}  // namespace

ParamReader::ParamReader(std::string method, const nlohmann::json& params)
    : method_(std::move(method)), params_(params.is_null() ? empty_object() : params) {
    if (!params_.is_object())
        throw ApiError::invalid_params(method_ + ": params must be an object with named members");
}

bool ParamReader::has(std::string_view key) const { return params_.find(key) != params_.end(); }

void ParamReader::fail(std::string_view key, const std::string& problem) const {
    throw ApiError::invalid_params(method_ + ": params." + std::string(key) + " " + problem);
}

const nlohmann::json* ParamReader::member(std::string_view key, bool required, const char* kind) {
    read_.emplace(key);
    if (!has(key)) {
        if (required) fail(key, std::string("is required (") + kind + ")");
        return nullptr;
    }
    // null is a value of the wrong type, never "the default": leave the member out for that.
    const nlohmann::json& v = *params_.find(key);
    if (v.is_null()) fail(key, std::string("is null; give ") + kind + (required ? "" : " or leave it out"));
    return &v;
}

std::string ParamReader::string(std::string_view key) {
    const auto* v = member(key, true, "a string");
    if (!v->is_string()) fail(key, "must be a string");
    return v->get<std::string>();
}

std::optional<std::string> ParamReader::string_opt(std::string_view key) {
    const auto* v = member(key, false, "a string");
    if (!v) return std::nullopt;
    if (!v->is_string()) fail(key, "must be a string");
    return v->get<std::string>();
}

bool ParamReader::boolean_or(std::string_view key, bool fallback) {
    const auto* v = member(key, false, "true or false");
    if (!v) return fallback;
    if (!v->is_boolean()) fail(key, "must be true or false");
    return v->get<bool>();
}

std::int64_t ParamReader::integer_or(std::string_view key, std::int64_t fallback, std::int64_t min,
                                     std::int64_t max) {
    const auto* v = member(key, false, "a whole number");
    if (!v) return fallback;
    if (!v->is_number_integer()) fail(key, "must be a whole number");
    const auto value = v->get<std::int64_t>();
    if (value < min || value > max)
        fail(key, "must be in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " +
                      std::to_string(value));
    return value;
}

double ParamReader::number_or(std::string_view key, double fallback, double min, double max) {
    const auto* v = member(key, false, "a number");
    if (!v) return fallback;
    if (!v->is_number()) fail(key, "must be a number");
    const double value = v->get<double>();
    if (!std::isfinite(value) || value < min || value > max) {
        std::ostringstream msg;
        msg << "must be in [" << min << ", " << max << "], got " << value;
        fail(key, msg.str());
    }
    return value;
}

const nlohmann::json& ParamReader::object(std::string_view key) {
    const auto* v = member(key, true, "an object");
    if (!v->is_object()) fail(key, "must be an object");
    return *v;
}

const nlohmann::json& ParamReader::array(std::string_view key) {
    const auto* v = member(key, true, "a list");
    if (!v->is_array()) fail(key, "must be a list");
    return *v;
}

void ParamReader::finish() const {
    for (const auto& [key, value] : params_.items())
        if (!read_.contains(key)) fail(key, "is not a parameter of " + method_);
}

}  // namespace fibrecell::api
