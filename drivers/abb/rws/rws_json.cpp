#include "drivers/abb/rws/rws_json.hpp"

#include <stdexcept>

namespace fibrecell::drivers::abb::rws::json {

Json item(std::string_view type, std::string_view title) {
    Json j = Json::object();
    j["_type"] = std::string(type);
    j["_title"] = std::string(title);
    return j;
}

Json state_document(std::string_view base_href, Json items) {
    Json doc = Json::object();
    doc["_links"]["base"]["href"] = std::string(base_href);
    doc["_embedded"]["_state"] = std::move(items);
    return doc;
}

const Json& state_items(const Json& document) {
    if (!document.is_object()) throw std::runtime_error("the response is not a JSON object");
    const auto e = document.find("_embedded");
    if (e == document.end() || !e->is_object())
        throw std::runtime_error("the response has no _embedded object");
    const auto s = e->find("_state");
    if (s == e->end() || !s->is_array())
        throw std::runtime_error("the response has no _embedded._state list");
    return *s;
}

std::optional<std::string> text_field(const Json& item, std::string_view key) {
    if (!item.is_object()) return std::nullopt;
    const auto it = item.find(std::string(key));
    if (it == item.end()) return std::nullopt;
    if (it->is_string()) return it->get<std::string>();
    if (it->is_number_integer()) return std::to_string(it->get<long long>());
    if (it->is_number()) return it->dump();
    if (it->is_boolean()) return it->get<bool>() ? "true" : "false";
    return std::nullopt;
}

std::string wire_text(const Json& document) {
    return document.dump(-1, ' ', false, Json::error_handler_t::replace);
}

Json status_document(long long code, std::string_view msg) {
    Json doc = Json::object();
    doc["status"]["code"] = code;
    doc["status"]["msg"] = std::string(msg);
    return doc;
}

namespace {

std::optional<Status> status_from(const Json& j) {
    if (!j.is_object()) return std::nullopt;
    const auto s = j.find("status");
    if (s == j.end() || !s->is_object()) return std::nullopt;
    Status out;
    if (const auto code = text_field(*s, "code")) {
        try {
            out.code = std::stoll(*code);
        } catch (const std::exception&) {
            out.code = 0;
        }
    }
    out.msg = text_field(*s, "msg").value_or("");
    return out;
}

// <span class="code">-1073445865</span> <span class="msg">...</span>
std::optional<std::string> xhtml_span(std::string_view body, std::string_view cls) {
    const std::string open = "class=\"" + std::string(cls) + "\">";
    const auto a = body.find(open);
    if (a == std::string_view::npos) return std::nullopt;
    const auto start = a + open.size();
    const auto end = body.find('<', start);
    if (end == std::string_view::npos) return std::nullopt;
    return std::string(body.substr(start, end - start));
}

}  // namespace

std::optional<Status> parse_status(std::string_view body) {
    const Json j = Json::parse(body, nullptr, false);
    if (!j.is_discarded()) {
        if (auto s = status_from(j)) return s;
        if (j.is_object() && j.contains("_embedded")) {
            if (auto s = status_from(j["_embedded"])) return s;
        }
        return std::nullopt;
    }
    const auto msg = xhtml_span(body, "msg");
    if (!msg) return std::nullopt;
    Status out;
    out.msg = *msg;
    if (const auto code = xhtml_span(body, "code")) {
        try {
            out.code = std::stoll(*code);
        } catch (const std::exception&) {
            out.code = 0;
        }
    }
    return out;
}

}  // namespace fibrecell::drivers::abb::rws::json
