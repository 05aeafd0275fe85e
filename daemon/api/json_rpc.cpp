#include "daemon/api/json_rpc.hpp"

#include "daemon/api/api_error.hpp"

#include <algorithm>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace fibrecell::api {

namespace {

bool valid_id(const nlohmann::json& id) {
    return id.is_string() || id.is_number() || id.is_null();
}

CheckedRequest invalid(const nlohmann::json& id, const std::string& why) {
    return {std::nullopt, error_response(id, errc::invalid_request, "invalid request: " + why)};
}

// nlohmann's message without its "[json.exception.parse_error.101] " prefix: the code says it.
std::string json_error_text(const nlohmann::json::exception& e) {
    std::string what = e.what();
    const auto close = what.find("] ");
    if (what.rfind("[json.exception.", 0) == 0 && close != std::string::npos)
        what = what.substr(close + 2);
    return what;
}

// The first key that appears twice in one object, as a path ("params.job"; "[2].params.job" in a
// batch). JSON leaves duplicates to the reader and nlohmann keeps the last: a request that says
// {"job": 1, "job": null} must not be read as either.
class DuplicateKeyScan {
  public:
    bool operator()(int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
        using E = nlohmann::json::parse_event_t;
        switch (event) {
            case E::object_start: levels_.push_back({true}); break;
            case E::array_start: levels_.push_back({false}); break;
            case E::object_end:
            case E::array_end:
                levels_.pop_back();
                if (!levels_.empty() && !levels_.back().object) ++levels_.back().index;
                break;
            case E::key: {
                Level& l = levels_.back();
                l.key = parsed.get<std::string>();
                if (!l.keys.insert(l.key).second && !first_) first_ = path();
                break;
            }
            case E::value:
                if (!levels_.empty() && !levels_.back().object) ++levels_.back().index;
                break;
        }
        return true;
    }
    const std::optional<std::string>& first() const { return first_; }

  private:
    struct Level {
        bool object;
        std::set<std::string> keys{};
        std::string key{};
        std::size_t index = 0;
    };
    std::string path() const {
        std::string p;
        for (const Level& l : levels_)
            p += l.object ? (p.empty() ? "" : ".") + l.key : "[" + std::to_string(l.index) + "]";
        return p;
    }
    std::vector<Level> levels_;
    std::optional<std::string> first_;
};

// The refusal of a message with a duplicate key: invalid params when the key is a call's
// parameter (with the call's id and method when they can be read), else an invalid request.
nlohmann::json duplicate_key_error(const nlohmann::json& message, const std::string& path) {
    const auto params_at = path.find("params.");
    const bool single = message.is_object();
    if (!single || params_at != 0) {
        return error_response(nullptr, errc::invalid_request,
                              "invalid request: " + path + " appears twice in one object");
    }
    const auto id = message.find("id");
    const auto method = message.find("method");
    const std::string name = method != message.end() && method->is_string() ? method->get<std::string>() + ": " : "";
    return error_response(id != message.end() && valid_id(*id) ? *id : nlohmann::json(),
                          errc::invalid_params, name + path + " appears twice; give it once");
}

}  // namespace

CheckedRequest check_request(nlohmann::json&& element) {
    if (!element.is_object()) return invalid(nullptr, "a request must be a JSON object");
    nlohmann::json id = nullptr;
    const auto id_it = element.find("id");
    const bool notification = id_it == element.end();
    if (!notification) {
        if (!valid_id(*id_it)) return invalid(nullptr, "id must be a string, a number or null");
        id = *id_it;
    }
    const auto version = element.find("jsonrpc");
    if (version == element.end() || *version != "2.0")
        return invalid(id, "\"jsonrpc\" must be \"2.0\"");
    const auto method = element.find("method");
    if (method == element.end() || !method->is_string())
        return invalid(id, "\"method\" must be a string");
    RpcRequest r;
    r.method = method->get<std::string>();
    r.id = std::move(id);
    r.notification = notification;
    for (const auto& [key, value] : element.items())
        if (key != "jsonrpc" && key != "method" && key != "params" && key != "id")
            return invalid(r.id, "unknown member \"" + key + "\"");
    const auto params = element.find("params");
    if (params == element.end()) {
        r.params = nlohmann::json::object();
    } else if (params->is_object() || params->is_array()) {
        r.params = std::move(*params);
    } else {
        return invalid(r.id, "\"params\" must be an object or an array");
    }
    return {std::move(r), nullptr};
}

std::size_t nesting_depth(std::string_view text) {
    std::size_t depth = 0;
    std::size_t deepest = 0;
    bool in_string = false;
    bool escaped = false;
    for (const char ch : text) {
        if (in_string) {
            if (escaped)
                escaped = false;
            else if (ch == '\\')
                escaped = true;
            else if (ch == '"')
                in_string = false;
        } else if (ch == '"') {
            in_string = true;
        } else if (ch == '[' || ch == '{') {
            deepest = std::max(deepest, ++depth);
        } else if ((ch == ']' || ch == '}') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}

ParsedLine parse_line(std::string_view line) {
    if (nesting_depth(line) > kMaxNestingDepth)
        return {nullptr, error_response(nullptr, errc::invalid_request,
                                        "invalid request: JSON nested deeper than " +
                                            std::to_string(kMaxNestingDepth) + " levels")};
    try {
        DuplicateKeyScan scan;
        nlohmann::json message = nlohmann::json::parse(line, std::ref(scan));
        if (scan.first()) return {nullptr, duplicate_key_error(message, *scan.first())};
        return {std::move(message), nullptr};
    } catch (const nlohmann::json::exception& e) {
        // parse_error for the syntax; out_of_range (406) for a number beyond double, which the
        // grammar allows but no value here can hold.
        return {nullptr, error_response(nullptr, errc::parse_error, json_error_text(e))};
    }
}

nlohmann::json result_response(const nlohmann::json& id, nlohmann::json result) {
    return {{"jsonrpc", "2.0"}, {"id", id}, {"result", std::move(result)}};
}

nlohmann::json error_response(const nlohmann::json& id, int code, const std::string& message,
                              const nlohmann::json& data) {
    nlohmann::json error = {{"code", code}, {"message", message}};
    if (!data.is_null()) error["data"] = data;
    return {{"jsonrpc", "2.0"}, {"id", id}, {"error", std::move(error)}};
}

nlohmann::json notification_message(const std::string& method, nlohmann::json params) {
    return {{"jsonrpc", "2.0"}, {"method", method}, {"params", std::move(params)}};
}

nlohmann::json request_message(const nlohmann::json& id, const std::string& method,
                               nlohmann::json params) {
    return {{"jsonrpc", "2.0"}, {"id", id}, {"method", method}, {"params", std::move(params)}};
}

std::string to_line(const nlohmann::json& message) {
    std::string line = message.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    line.push_back('\n');
    return line;
}

}  // namespace fibrecell::api
