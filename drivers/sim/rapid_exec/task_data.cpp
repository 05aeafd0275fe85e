#include "drivers/sim/rapid_exec/task_data.hpp"

#include "drivers/abb/rapid/evaluate.hpp"
#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/predefined.hpp"
#include "drivers/abb/rapid/types.hpp"

#include <cmath>

namespace fibrecell::drivers::sim::rapid_exec {

namespace {

std::string canonical_type(const std::string& type) {
    const rapid::TypeInfo* t = rapid::find_type(type);
    return t != nullptr ? std::string(t->name) : type;
}

}  // namespace

rapid::Value initial_value(const rapid::DataDecl& d, const Variable& v,
                           const std::function<rapid::Value(const rapid::Expr&)>& eval) {
    if (d.value) return *d.value;
    if (d.init) {
        std::string why;
        auto fitted = rapid::conform_array(eval(*d.init), v.type, v.extents, &why);
        if (!fitted) throw RuntimeError(d.line, "initial value of " + d.name + ": " + why);
        return std::move(*fitted);
    }
    auto def = rapid::default_value(v.type, v.extents);
    if (!def) throw RuntimeError(d.line, "type " + d.type + " is not executed");
    return std::move(*def);
}

std::shared_ptr<LoadedModule> instantiate(std::shared_ptr<const rapid::Module> module,
                                          bool dynamic, std::string path) {
    auto m = std::make_shared<LoadedModule>();
    m->module = std::move(module);
    m->dynamic = dynamic;
    m->path = std::move(path);
    // Initialisers the reader could not evaluate see the module's earlier data.
    const rapid::EvalContext context{
        .lookup = [&](std::string_view name) -> const rapid::Value* {
            auto it = m->data.find(rapid::fold(name));
            if (it != m->data.end()) return &it->second.value;
            const rapid::PredefinedData* p = rapid::predefined_data(name);
            return p != nullptr ? &p->value : nullptr;
        },
        .call = {}};
    for (const rapid::DataDecl& d : m->module->data) {
        Variable v;
        v.name = d.name;
        v.type = canonical_type(d.type);
        v.storage = d.storage;
        v.local = d.visibility == rapid::Visibility::local;
        v.read_only = d.storage == rapid::Storage::constant;
        try {
            v.extents = d.extents.empty() && !d.dims.empty()
                            ? rapid::evaluate_extents(d.dims, context)
                            : d.extents;
            v.value = initial_value(
                d, v, [&](const rapid::Expr& init) { return rapid::evaluate(init, context); });
        } catch (const rapid::EvalError& e) {
            throw RuntimeError(e.line(), e.what());
        }
        v.initial = v.value;
        m->data[rapid::fold(d.name)] = std::move(v);
    }
    return m;
}

Slot slot_of(Variable& variable) {
    return Slot{.value = &variable.value,
                .type = variable.type,
                .extents = variable.extents,
                .read_only = variable.read_only,
                .what = variable.name};
}

void assign(const Slot& slot, const rapid::Value& value, std::size_t line) {
    if (slot.read_only) throw RuntimeError(line, "'" + slot.what + "' cannot be written");
    std::string why;
    auto fitted = rapid::conform_array(value, slot.type, slot.extents, &why);
    if (!fitted)
        throw RuntimeError(line, "cannot assign " + rapid::to_rapid_text(value) + " to '" +
                                     slot.what + "' (" + slot.type + "): " + why);
    *slot.value = std::move(*fitted);
}

Slot component_slot(const Slot& base, const std::string& component, std::size_t line) {
    if (!base.extents.empty())
        throw RuntimeError(line, "'" + base.what + "' is an array, it has no component '" +
                                     component + "'");
    rapid::Value* v = rapid::component(*base.value, component);
    if (v == nullptr)
        throw RuntimeError(line, base.type + " has no component '" + component + "'");
    return Slot{.value = v,
                .type = std::string(rapid::field_type(base.type, component)),
                .extents = {},
                .read_only = base.read_only,
                .what = base.what + "." + component};
}

Slot element_slot(const Slot& base, const rapid::Value& index, std::size_t line) {
    if (base.extents.empty() || !base.value->is_items())
        throw RuntimeError(line, "'" + base.what + "' is not an array");
    auto& items = base.value->items();
    if (!index.is_num() || index.num() != std::trunc(index.num()) || index.num() < 1 ||
        index.num() > static_cast<double>(items.size()))
        throw RuntimeError(line, "index " + rapid::to_rapid_text(index) + " of '" + base.what +
                                     "' outside 1.." + std::to_string(items.size()));
    const auto i = static_cast<std::size_t>(index.num());
    return Slot{.value = &items[i - 1],
                .type = base.type,
                .extents = {base.extents.begin() + 1, base.extents.end()},
                .read_only = base.read_only,
                .what = base.what + "{" + std::to_string(i) + "}"};
}

}  // namespace fibrecell::drivers::sim::rapid_exec
