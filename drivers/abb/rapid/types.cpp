#include "drivers/abb/rapid/types.hpp"

#include "drivers/abb/rapid/names.hpp"

namespace fibrecell::drivers::abb::rapid {
namespace {

// Component order as in the RAPID reference and docs/rapid-subset.md ("Records").
constexpr Field pos_fields[] = {{"x", "num"}, {"y", "num"}, {"z", "num"}};
constexpr Field orient_fields[] = {{"q1", "num"}, {"q2", "num"}, {"q3", "num"}, {"q4", "num"}};
constexpr Field pose_fields[] = {{"trans", "pos"}, {"rot", "orient"}};
constexpr Field confdata_fields[] = {
    {"cf1", "num"}, {"cf4", "num"}, {"cf6", "num"}, {"cfx", "num"}};
constexpr Field extjoint_fields[] = {{"eax_a", "num"}, {"eax_b", "num"}, {"eax_c", "num"},
                                     {"eax_d", "num"}, {"eax_e", "num"}, {"eax_f", "num"}};
constexpr Field robjoint_fields[] = {{"rax_1", "num"}, {"rax_2", "num"}, {"rax_3", "num"},
                                     {"rax_4", "num"}, {"rax_5", "num"}, {"rax_6", "num"}};
constexpr Field robtarget_fields[] = {
    {"trans", "pos"}, {"rot", "orient"}, {"robconf", "confdata"}, {"extax", "extjoint"}};
constexpr Field jointtarget_fields[] = {{"robax", "robjoint"}, {"extax", "extjoint"}};
constexpr Field loaddata_fields[] = {{"mass", "num"}, {"cog", "pos"}, {"aom", "orient"},
                                     {"ix", "num"},   {"iy", "num"},  {"iz", "num"}};
constexpr Field tooldata_fields[] = {
    {"robhold", "bool"}, {"tframe", "pose"}, {"tload", "loaddata"}};
constexpr Field wobjdata_fields[] = {{"robhold", "bool"},
                                     {"ufprog", "bool"},
                                     {"ufmec", "string"},
                                     {"uframe", "pose"},
                                     {"oframe", "pose"}};
constexpr Field speeddata_fields[] = {
    {"v_tcp", "num"}, {"v_ori", "num"}, {"v_leax", "num"}, {"v_reax", "num"}};
constexpr Field zonedata_fields[] = {
    {"finep", "bool"},   {"pzone_tcp", "num"}, {"pzone_ori", "num"}, {"pzone_eax", "num"},
    {"zone_ori", "num"}, {"zone_leax", "num"}, {"zone_reax", "num"}};

const TypeInfo types[] = {
    {"num", TypeKind::num, {}},
    {"dnum", TypeKind::num, {}},
    {"intnum", TypeKind::num, {}},
    {"errnum", TypeKind::num, {}},
    {"dionum", TypeKind::num, {}},
    {"byte", TypeKind::num, {}},
    {"bool", TypeKind::boolean, {}},
    {"string", TypeKind::string, {}},
    {"pos", TypeKind::record, pos_fields},
    {"orient", TypeKind::record, orient_fields},
    {"pose", TypeKind::record, pose_fields},
    {"confdata", TypeKind::record, confdata_fields},
    {"extjoint", TypeKind::record, extjoint_fields},
    {"robjoint", TypeKind::record, robjoint_fields},
    {"robtarget", TypeKind::record, robtarget_fields},
    {"jointtarget", TypeKind::record, jointtarget_fields},
    {"loaddata", TypeKind::record, loaddata_fields},
    {"tooldata", TypeKind::record, tooldata_fields},
    {"wobjdata", TypeKind::record, wobjdata_fields},
    {"speeddata", TypeKind::record, speeddata_fields},
    {"zonedata", TypeKind::record, zonedata_fields},
    {"triggdata", TypeKind::opaque, {}},
    {"signaldo", TypeKind::opaque, {}},
    {"signaldi", TypeKind::opaque, {}},
    {"signalgo", TypeKind::opaque, {}},
    {"signalgi", TypeKind::opaque, {}},
    {"signalao", TypeKind::opaque, {}},
    {"signalai", TypeKind::opaque, {}},
    {"loadsession", TypeKind::opaque, {}},
    {"clock", TypeKind::opaque, {}},
};

}  // namespace

const TypeInfo* find_type(std::string_view name) {
    for (const TypeInfo& t : types)
        if (same_name(t.name, name)) return &t;
    return nullptr;
}

std::optional<std::size_t> field_index(std::string_view type, std::string_view component) {
    const TypeInfo* t = find_type(type);
    if (t == nullptr) return std::nullopt;
    for (std::size_t i = 0; i < t->fields.size(); ++i)
        if (same_name(t->fields[i].name, component)) return i;
    return std::nullopt;
}

std::string_view field_type(std::string_view type, std::string_view component) {
    const TypeInfo* t = find_type(type);
    if (t == nullptr) return {};
    const auto i = field_index(type, component);
    return i ? t->fields[*i].type : std::string_view{};
}

bool is_num_type(std::string_view type) {
    const TypeInfo* t = find_type(type);
    return t != nullptr && t->kind == TypeKind::num;
}

bool is_signal_type(std::string_view type) {
    return type.size() == 8 && same_name(type.substr(0, 6), "signal");
}

bool compatible_types(std::string_view expected, std::string_view actual) {
    if (expected.empty() || actual.empty() || expected == "any") return true;
    if (same_name(expected, actual)) return true;
    if (is_num_type(expected) && is_num_type(actual)) return true;
    // "signal" stands for any signal type in the instruction tables.
    if (same_name(expected, "signal") && is_signal_type(actual)) return true;
    return false;
}

}  // namespace fibrecell::drivers::abb::rapid
