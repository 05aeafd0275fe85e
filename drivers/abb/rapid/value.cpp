#include "drivers/abb/rapid/value.hpp"

#include <cmath>
#include <cstdio>

#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/types.hpp"

namespace fibrecell::drivers::abb::rapid {
namespace {

std::string describe(const Value& v) {
    if (v.is_num()) return "a number";
    if (v.is_bool()) return "a bool";
    if (v.is_string()) return "a string";
    if (v.is_items()) return "an aggregate of " + std::to_string(v.items().size()) + " items";
    return "no value";
}

void set_problem(std::string* problem, std::string text) {
    if (problem != nullptr) *problem = std::move(text);
}

}  // namespace

Value num_value(double v) {
    return Value{v, "num"};
}
Value bool_value(bool v) {
    return Value{v, "bool"};
}
Value string_value(std::string v) {
    return Value{std::move(v), "string"};
}
Value items_value(Value::Items items, std::string type) {
    return Value{std::move(items), std::move(type)};
}

std::optional<Value> conform(const Value& value, std::string_view type, std::string* problem) {
    const TypeInfo* t = find_type(type);
    if (t == nullptr) {
        set_problem(problem, "unknown type '" + std::string(type) + "'");
        return std::nullopt;
    }
    const std::string name(t->name);
    switch (t->kind) {
        case TypeKind::num:
            if (value.is_num()) return Value{value.data, name};
            break;
        case TypeKind::boolean:
            if (value.is_bool()) return Value{value.data, name};
            break;
        case TypeKind::string:
            if (value.is_string()) return Value{value.data, name};
            break;
        case TypeKind::opaque:
            set_problem(problem, name + " has no literal value");
            return std::nullopt;
        case TypeKind::record: {
            if (!value.is_items()) break;
            const Value::Items& in = value.items();
            if (in.size() != t->fields.size()) {
                set_problem(problem, name + ": expected " + std::to_string(t->fields.size()) +
                                         " items, found " + std::to_string(in.size()));
                return std::nullopt;
            }
            Value::Items out;
            out.reserve(in.size());
            for (std::size_t i = 0; i < in.size(); ++i) {
                std::string inner;
                auto item = conform(in[i], t->fields[i].type, &inner);
                if (!item) {
                    set_problem(problem, "component " + std::to_string(i + 1) + " (" +
                                             std::string(t->fields[i].name) + ") of " + name +
                                             ": " + inner);
                    return std::nullopt;
                }
                out.push_back(std::move(*item));
            }
            return items_value(std::move(out), name);
        }
    }
    set_problem(problem, "expected " + name + ", found " + describe(value));
    return std::nullopt;
}

bool has_shape(const Value& value, std::string_view type) {
    const TypeInfo* t = find_type(type);
    if (t == nullptr) return false;
    switch (t->kind) {
        case TypeKind::num:
            return value.is_num();
        case TypeKind::boolean:
            return value.is_bool();
        case TypeKind::string:
            return value.is_string();
        case TypeKind::opaque:
            return false;
        case TypeKind::record: {
            if (!value.is_items() || value.items().size() != t->fields.size()) return false;
            for (std::size_t i = 0; i < t->fields.size(); ++i)
                if (!has_shape(value.items()[i], t->fields[i].type)) return false;
            return true;
        }
    }
    return false;
}

std::optional<Value> conform_array(const Value& value, std::string_view type,
                                   const std::vector<std::size_t>& extents, std::string* problem) {
    if (extents.empty()) return conform(value, type, problem);
    if (!value.is_items() || value.items().size() != extents.front()) {
        set_problem(problem, "array dimension of " + std::to_string(extents.front()) + ": found " +
                                 describe(value));
        return std::nullopt;
    }
    const std::vector<std::size_t> inner(extents.begin() + 1, extents.end());
    Value::Items out;
    out.reserve(value.items().size());
    for (std::size_t i = 0; i < value.items().size(); ++i) {
        std::string why;
        auto item = conform_array(value.items()[i], type, inner, &why);
        if (!item) {
            set_problem(problem, "element " + std::to_string(i + 1) + ": " + why);
            return std::nullopt;
        }
        out.push_back(std::move(*item));
    }
    return items_value(std::move(out));
}

std::optional<Value> default_value(std::string_view type, const std::vector<std::size_t>& extents) {
    if (!extents.empty()) {
        auto element = default_value(type, {extents.begin() + 1, extents.end()});
        if (!element) return std::nullopt;
        return items_value(Value::Items(extents.front(), *element));
    }
    const TypeInfo* t = find_type(type);
    if (t == nullptr) return std::nullopt;
    const std::string name(t->name);
    switch (t->kind) {
        case TypeKind::num:
            return Value{0.0, name};
        case TypeKind::boolean:
            return Value{false, name};
        case TypeKind::string:
            return Value{std::string(), name};
        case TypeKind::opaque:
            return Value{std::monostate{}, name};
        case TypeKind::record: {
            Value::Items items;
            for (const Field& f : t->fields) {
                auto item = default_value(f.type);
                if (!item) return std::nullopt;
                items.push_back(std::move(*item));
            }
            return items_value(std::move(items), name);
        }
    }
    return std::nullopt;
}

const Value* component(const Value& record, std::string_view name) {
    if (!record.is_items()) return nullptr;
    const auto i = field_index(record.type, name);
    if (!i || *i >= record.items().size()) return nullptr;
    return &record.items()[*i];
}

Value* component(Value& record, std::string_view name) {
    return const_cast<Value*>(component(static_cast<const Value&>(record), name));
}

std::string format_num(double v) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    if (v == std::trunc(v) && std::fabs(v) < 1e9) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.0f", v);
        return std::string(buf) == "-0" ? "0" : buf;
    }
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

std::string to_rapid_text(const Value& value) {
    if (value.is_num()) return format_num(value.num());
    if (value.is_bool()) return value.boolean() ? "TRUE" : "FALSE";
    if (value.is_string()) return "\"" + value.string() + "\"";
    if (value.is_items()) {
        std::string out = "[";
        for (std::size_t i = 0; i < value.items().size(); ++i) {
            if (i > 0) out += ",";
            out += to_rapid_text(value.items()[i]);
        }
        return out + "]";
    }
    return "";
}

}  // namespace fibrecell::drivers::abb::rapid
