// Data declarations and parameters: names, types, storage, dimensions and initial values.

#include "drivers/abb/rapid/evaluate.hpp"
#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/types.hpp"
#include "drivers/abb/rapid/validate_detail.hpp"

namespace fibrecell::drivers::abb::rapid::detail {
namespace {

// Names in an initialiser must be constants; functions must be ones evaluate() computes.
class ConstantCheck {
  public:
    ConstantCheck(Checker& c, const DataDecl& d) : c_(c), d_(d) {}

    bool operator()(const Expr& e) {
        std::visit([&](const auto& n) { visit(n, e.line); }, e.node);
        return ok_;
    }

  private:
    void visit(const Literal&, std::size_t) {}
    void visit(const NameRef& n, std::size_t line) {
        const auto s = c_.find_symbol(n.name);
        if (!s || s->storage == Storage::constant) return;  // undeclared is reported elsewhere
        c_.report(
            Rule::initializer, line,
            "initial value of '" + d_.name + "' uses " +
                (s->origin == Symbol::Origin::loop_variable ? std::string("a loop variable")
                                                            : std::string(to_string(s->storage))) +
                " '" + n.name + "'; initial values must be constant");
        ok_ = false;
    }
    void visit(const Aggregate& a, std::size_t) {
        for (const Expr& i : a.items) (*this)(i);
    }
    void visit(const ComponentAccess& c, std::size_t) { (*this)(*c.base); }
    void visit(const IndexAccess& i, std::size_t) {
        (*this)(*i.base);
        for (const Expr& e : i.indices) (*this)(e);
    }
    void visit(const Unary& u, std::size_t) { (*this)(*u.operand); }
    void visit(const Binary& b, std::size_t) {
        (*this)(*b.lhs);
        (*this)(*b.rhs);
    }
    void visit(const FunctionCall& f, std::size_t line) {
        if (!is_pure_builtin(f.name)) {
            c_.report(Rule::initializer, line,
                      "initial value of '" + d_.name + "' calls " + f.name +
                          ", which is not a constant function");
            ok_ = false;
        }
        for (const Argument& a : f.args)
            if (a.value) (*this)(*a.value);
    }

    Checker& c_;
    const DataDecl& d_;
    bool ok_ = true;
};

}  // namespace

void Checker::check_params(const Routine& r) {
    for (std::size_t i = 0; i < r.params.size(); ++i) {
        const Param& p = r.params[i];
        check_declared_name(p.name, p.line, "a parameter");
        if (find_type(p.type) == nullptr && !same_name(p.type, "switch"))
            report(Rule::unknown_type, p.line,
                   "parameter type '" + p.type + "' is not in the subset");
        for (std::size_t j = 0; j < i; ++j)
            if (same_name(r.params[j].name, p.name))
                report(Rule::duplicate_name, p.line, "parameter '" + p.name + "' repeated");
    }
}

void Checker::check_declarations(const std::vector<DataDecl>& decls, bool module_level) {
    for (std::size_t i = 0; i < decls.size(); ++i) {
        const DataDecl& d = decls[i];
        // Declared before use: an initialiser sees the declarations above it only.
        (module_level ? visible_module_data_ : visible_locals_) = i;
        check_declared_name(d.name, d.line, "data");
        if (!module_level) {
            for (const Param& p : routine_->params)
                if (same_name(p.name, d.name))
                    report(Rule::duplicate_name, d.line,
                           "'" + d.name + "' is already a parameter of " + routine_->name);
            for (std::size_t j = 0; j < i; ++j)
                if (same_name(decls[j].name, d.name))
                    report(Rule::duplicate_name, d.line,
                           "'" + d.name + "' is already declared on line " +
                               std::to_string(decls[j].line));
        }
        for (const Expr& dim : d.dims) check_names(dim);
        if (d.init) check_names(*d.init);

        const TypeInfo* type = find_type(d.type);
        if (type == nullptr) {
            report(Rule::unknown_type, d.line, "data type '" + d.type + "' is not in the subset");
            continue;
        }
        if (type->kind == TypeKind::opaque && d.storage != Storage::var)
            report(Rule::declaration, d.line,
                   std::string(type->name) + " data can only be VAR ('" + d.name + "')");
        if (d.storage == Storage::constant && !d.init)
            report(Rule::declaration, d.line, "CONST '" + d.name + "' needs an initial value");

        std::vector<std::size_t> extents;
        bool ok = true;
        if (!d.dims.empty()) {
            for (const Expr& dim : d.dims) ok = ConstantCheck(*this, d)(dim) && ok;
            if (ok) {
                try {
                    extents = evaluate_extents(d.dims, constant_context());
                } catch (const EvalError& e) {
                    report(Rule::declaration, d.line,
                           "dimension of '" + d.name + "': " + std::string(e.what()));
                    ok = false;
                }
            }
        }
        if (!d.init || !ok || !ConstantCheck(*this, d)(*d.init)) continue;
        Value value;
        try {
            value = evaluate_constant(*d.init);
        } catch (const EvalError& e) {
            report(Rule::initializer, e.line(),
                   "initial value of '" + d.name + "': " + std::string(e.what()));
            continue;
        }
        std::string problem;
        const auto typed = conform_array(value, d.type, extents, &problem);
        if (!typed) {
            report(Rule::aggregate_shape, d.line,
                   "initial value of '" + d.name + "' does not fit " + std::string(type->name) +
                       (extents.empty() ? "" : " array") + ": " + problem);
            continue;
        }
        check_value(type->name, *typed, &*d.init, d.line, "'" + d.name + "'");
    }
    (module_level ? visible_module_data_ : visible_locals_) = decls.size();
}

}  // namespace fibrecell::drivers::abb::rapid::detail
