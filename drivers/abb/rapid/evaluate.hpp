#pragma once
// Expression evaluation, shared by the reader (constant initialisers), the validator and a
// simulated controller (which supplies the current data values and the functions that read I/O
// or robot state). RAPID semantics: trig functions in degrees, DIV/MOD on integers, strings at
// most 80 characters, no short-circuit in AND/OR.

#include <cstddef>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "drivers/abb/rapid/program.hpp"
#include "drivers/abb/rapid/value.hpp"

namespace fibrecell::drivers::abb::rapid {

// A run-time error of the evaluated program (the controller would raise an ERR_... here).
class EvalError : public std::runtime_error {
  public:
    EvalError(std::size_t line, const std::string& message)
        : std::runtime_error(message), line_(line) {}
    std::size_t line() const { return line_; }

  private:
    std::size_t line_;
};

struct EvalContext {
    // The current value of the data called `name` (case-insensitive); nullptr when unknown.
    std::function<const Value*(std::string_view name)> lookup;
    // Functions beyond the pure built-ins (DInput, CRobT, the module's FUNCs); return nothing to
    // fall back to the built-ins. May be empty.
    std::function<std::optional<Value>(const FunctionCall& call, std::size_t line)> call;
};

// Throws EvalError with the expression's line on any run-time error.
Value evaluate(const Expr& expr, const EvalContext& context);

// Whether evaluate() computes `function` itself (Abs, Round, Offs, NumToStr, ...).
bool is_pure_builtin(std::string_view function);

// Arrays larger than this are refused (a typo in a dimension must not exhaust memory).
inline constexpr std::size_t max_array_elements = 100000;

// Evaluates array dimensions ({10}, {2, 3}): positive integers whose product is at most
// max_array_elements. Throws EvalError otherwise.
std::vector<std::size_t> evaluate_extents(const std::vector<Expr>& dims,
                                          const EvalContext& context);

}  // namespace fibrecell::drivers::abb::rapid
