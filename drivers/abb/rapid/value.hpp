#pragma once
// A RAPID value as the reader and a simulator hold it: num (and dnum) as double, bool, string, or
// a list of items for records and arrays. Records carry their type name so that components can be
// reached by name ("p.trans.x"); an aggregate literal is untyped until conform() fits it to a type.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace fibrecell::drivers::abb::rapid {

struct Value {
    using Items = std::vector<Value>;
    // monostate: opaque data (triggdata, signals, loadsession) that has no literal value.
    std::variant<std::monostate, double, bool, std::string, Items> data;
    // Canonical type name ("robtarget", "num"); "" for an untyped aggregate or an array.
    std::string type;

    bool is_num() const { return std::holds_alternative<double>(data); }
    bool is_bool() const { return std::holds_alternative<bool>(data); }
    bool is_string() const { return std::holds_alternative<std::string>(data); }
    bool is_items() const { return std::holds_alternative<Items>(data); }
    double num() const { return std::get<double>(data); }
    bool boolean() const { return std::get<bool>(data); }
    const std::string& string() const { return std::get<std::string>(data); }
    const Items& items() const { return std::get<Items>(data); }
    Items& items() { return std::get<Items>(data); }

    bool operator==(const Value& other) const { return data == other.data; }
};

Value num_value(double v);
Value bool_value(bool v);
Value string_value(std::string v);
Value items_value(Value::Items items, std::string type = {});

// Fits `value` to `type`: checks the aggregate's shape and item types recursively and names every
// record. On a mismatch returns nothing and, when `problem` is given, says where
// ("component 2 (rot) of robtarget: expected 4 items, found 3").
std::optional<Value> conform(const Value& value, std::string_view type,
                             std::string* problem = nullptr);

// Whether conform() would succeed, without building the typed copy.
bool has_shape(const Value& value, std::string_view type);

// Same for an array declared with `extents` ({10} or {2, 3}): nested aggregates of those sizes.
std::optional<Value> conform_array(const Value& value, std::string_view type,
                                   const std::vector<std::size_t>& extents,
                                   std::string* problem = nullptr);

// The value a declaration without initialiser starts with: 0, FALSE, "", records of those.
// Nothing for a type outside the subset.
std::optional<Value> default_value(std::string_view type,
                                   const std::vector<std::size_t>& extents = {});

// A record component by name; nullptr when `record` is not a record with that component.
const Value* component(const Value& record, std::string_view name);
Value* component(Value& record, std::string_view name);

// ValToStr-style text: numbers with up to 6 significant digits, strings quoted, records as
// aggregates "[[1,2,3],[1,0,0,0]]".
std::string to_rapid_text(const Value& value);

// A num printed the way RAPID prints it (integers without decimals, else 6 significant digits).
std::string format_num(double v);

}  // namespace fibrecell::drivers::abb::rapid
