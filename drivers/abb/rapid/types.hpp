#pragma once
// The RAPID data types the reader knows: atomic types, the record types (docs/rapid-subset.md,
// "Records") with their components in declaration order, and the opaque types (signals,
// triggdata, ...) that hold no value the program can write as a literal.

#include <optional>
#include <span>
#include <string_view>

namespace fibrecell::drivers::abb::rapid {

enum class TypeKind {
    num,  // num, dnum and the num aliases (intnum, errnum, dionum, byte)
    boolean,
    string,
    record,  // pos, orient, pose, confdata, robtarget, tooldata, ...
    opaque,  // triggdata, signaldo, loadsession, clock: declared, never written as a literal
};

struct Field {
    std::string_view name;
    std::string_view type;
};

struct TypeInfo {
    std::string_view name;  // canonical lower-case spelling: "robtarget"
    TypeKind kind = TypeKind::opaque;
    std::span<const Field> fields;  // records only, in aggregate order
};

// nullptr for a type outside the subset. Case-insensitive.
const TypeInfo* find_type(std::string_view name);

// Index of `component` in a record type ("robtarget", "rot" -> 1); nothing when absent.
std::optional<std::size_t> field_index(std::string_view type, std::string_view component);

// The type of a record component ("robtarget", "trans" -> "pos"); "" when unknown.
std::string_view field_type(std::string_view type, std::string_view component);

// num and dnum and their aliases are interchangeable for argument checks.
bool is_num_type(std::string_view type);
bool is_signal_type(std::string_view type);

// Whether a value of type `actual` may be passed where `expected` is wanted ("any" accepts all).
bool compatible_types(std::string_view expected, std::string_view actual);

}  // namespace fibrecell::drivers::abb::rapid
