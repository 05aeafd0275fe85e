// Initial values of declarations. RAPID initialisers are constant expressions: literals, CONST
// data declared earlier and predefined constants (v100, z10, pi). Anything else leaves `value`
// empty; the validator says why.

#include <map>

#include "drivers/abb/rapid/evaluate.hpp"
#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/parser_detail.hpp"
#include "drivers/abb/rapid/predefined.hpp"

namespace fibrecell::drivers::abb::rapid::detail {
namespace {

using Constants = std::map<std::string, Value>;  // folded name -> value

void fill(DataDecl& d, Constants& constants) {
    const EvalContext context{[&](std::string_view name) -> const Value* {
                                  if (auto it = constants.find(fold(name)); it != constants.end())
                                      return &it->second;
                                  const PredefinedData* p = predefined_data(name);
                                  return p != nullptr && p->constant ? &p->value : nullptr;
                              },
                              {}};
    try {
        d.extents = evaluate_extents(d.dims, context);
        if (d.init)
            d.value = conform_array(evaluate(*d.init, context), d.type, d.extents);
        else
            d.value = default_value(d.type, d.extents);
    } catch (const EvalError&) {
        d.extents.clear();
        d.value.reset();
    }
    if (d.storage == Storage::constant && d.value) constants[fold(d.name)] = *d.value;
}

}  // namespace

void evaluate_declarations(Module& module) {
    Constants constants;
    for (DataDecl& d : module.data) fill(d, constants);
    for (Routine& r : module.routines) {
        Constants local = constants;
        for (DataDecl& d : r.locals) fill(d, local);
    }
}

}  // namespace fibrecell::drivers::abb::rapid::detail
