#pragma once
// Internal to the validator: the checker that walks one module, split by concern over
// validate.cpp (module level), validate_names.cpp (scopes and name resolution),
// validate_declarations.cpp, validate_statements.cpp, validate_values.cpp, validate_triggers.cpp.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "drivers/abb/rapid/evaluate.hpp"
#include "drivers/abb/rapid/validate.hpp"

namespace fibrecell::drivers::abb::rapid::detail {

// What a name used as data resolves to.
struct Symbol {
    enum class Origin { module_data, local, param, loop_variable, predefined, signal, external };
    Origin origin = Origin::module_data;
    std::string type;  // "" when unknown (externally configured signals)
    Storage storage = Storage::var;
    bool is_array = false;
    bool in_param = false;           // an IN parameter (read-only is not enforced by RAPID)
    const DataDecl* decl = nullptr;  // module or routine data
};

class Checker {
  public:
    Checker(const Module& module, const ValidateOptions& options, std::vector<Diagnostic>& out);
    void run();

    // ---- reporting ----
    void report(Rule rule, std::size_t line, std::string message,
                Severity severity = Severity::error);

    // ---- names (validate_names.cpp) ----
    std::optional<Symbol> find_symbol(std::string_view name) const;
    // Why `name` does not resolve as data, for the undeclared message.
    std::string undeclared_reason(std::string_view name) const;
    bool is_callable_function(std::string_view name) const;
    // In ValidateOptions::external_routines ("Proc" or "Module:Proc"); `module` may be empty.
    bool is_external_routine(std::string_view name, std::string_view module = {}) const;
    std::string_view function_type(std::string_view name) const;
    // A name being declared must not hide predefined data or built-ins.
    void check_declared_name(std::string_view name, std::size_t line, std::string_view what);
    // Every name in `e` resolves (undeclared) and every component exists.
    void check_names(const Expr& e);
    // The static type of `e` where it is evident ("" when not).
    std::string static_type(const Expr& e) const;

    // ---- declarations (validate_declarations.cpp) ----
    void check_declarations(const std::vector<DataDecl>& decls, bool module_level);
    void check_params(const Routine& r);

    // ---- statements (validate_statements.cpp) ----
    void check_block(const Block& block);
    void check_statement(const Statement& s);
    void check_call(const ProcCall& call, std::size_t line);
    void check_late_call(const LateCall& call, std::size_t line);
    void check_assign(const Assign& a, std::size_t line);

    // ---- values (validate_values.cpp) ----
    // `e` against `type` (aggregate shape, or the static type of a name); then, when `e` is a
    // constant the validator can evaluate, the value rules (quaternion, speed, tool mass).
    // Returns false when a mismatch was reported.
    bool check_typed(const Expr& e, std::string_view type, std::string_view what);
    // Value rules on an evaluated value of `type`; `e` (may be null) supplies the literal text.
    void check_value(std::string_view type, const Value& value, const Expr* e, std::size_t line,
                     std::string_view what);
    // Evaluation over the constants visible now (CONST data, predefined constants).
    EvalContext constant_context() const;
    Value evaluate_constant(const Expr& e) const;  // throws EvalError
    // The value of a constant expression, or nothing (names of VAR/PERS data, I/O functions).
    std::optional<Value> constant_value(const Expr& e) const;

    // ---- triggers (validate_triggers.cpp) ----
    void check_triggers(const Routine& r);

    const Module& module_;
    const ValidateOptions& options_;
    std::vector<Diagnostic>& out_;
    std::string file_;

    // Scope while walking: data declared so far at module level (all of it inside routines), the
    // current routine, locals visible so far, and FOR variables from outermost to innermost.
    std::size_t visible_module_data_ = 0;
    const Routine* routine_ = nullptr;
    std::size_t visible_locals_ = 0;
    std::vector<std::string> loop_variables_;
};

// First positional argument, n-th positional argument (nullptr when absent).
const Expr* positional(const std::vector<Argument>& args, std::size_t n);

// The aggregate item at `path` inside `e` ([1, 1] = tframe.rot of a tooldata literal); nullptr
// when `e` is not an aggregate literal down that path.
const Expr* aggregate_item(const Expr* e, std::initializer_list<std::size_t> path);

}  // namespace fibrecell::drivers::abb::rapid::detail
