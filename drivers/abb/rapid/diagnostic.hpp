#pragma once
// What the RAPID reader and validator report: one diagnostic per problem, each naming the file, the
// line, the rule it breaks (a stable kebab-case id, e.g. "identifier-length") and the problem.

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace fibrecell::drivers::abb::rapid {

// The rules of docs/rapid-subset.md; to_string gives the stable id used in messages and docs.
enum class Rule {
    encoding,           // non-ASCII byte, BOM or control character
    line_ending,        // CR not followed by LF (CR CR LF, lone CR)
    line_count,         // more lines than the configured maximum (default 5000)
    syntax,             // anything the grammar of the subset does not accept
    block,              // MODULE/PROC/IF/... not closed, or closed by the wrong END keyword
    nesting_depth,      // expressions or blocks nested deeper than the reader allows
    identifier_length,  // identifier longer than 32 characters
    string_length,      // string literal longer than 80 characters
    reserved_word,      // reserved word used as a name
    builtin_name,       // declaration hides predefined data or a built-in instruction/function/type
    duplicate_name,     // the same name declared twice in one scope
    module_count,       // not exactly one module in the file
    module_name,        // module name differs from the file stem or clashes with a loaded module
    module_attribute,   // unknown, repeated or mutually exclusive module attribute
    declaration_order,  // routine data declared after the first statement
    declaration,        // ill-formed declaration (CONST without value, TASK on a VAR, ...)
    unknown_type,       // data type outside the subset
    undeclared,         // a name used but not declared before use
    argument_count,     // wrong number of positional arguments for a known instruction/routine
    optional_argument,  // optional argument or switch the instruction does not have
    argument_type,      // a declared name or aggregate of the wrong type passed to an instruction
    aggregate_shape,    // aggregate literal that does not fit its data type
    initializer,        // initial value that is not a constant expression
    const_assignment,   // assignment to a CONST, or to something that is not data
    quaternion_norm,    // |q| not within 1e-5 of 1
    quaternion_digits,  // quaternion component printed with fewer than 6 decimals
    speed,              // speeddata v_tcp <= 0
    tool_mass,          // tooldata load mass <= 0
    tool_cog,           // tooldata centre of gravity all zero (warning)
    trigger_setup,      // TriggL/TriggJ trigger not set up by TriggIO/TriggEquip/... earlier
    late_call,          // late-bound call to a literal name that is not known
};

std::string_view to_string(Rule rule);

enum class Severity { error, warning };

struct Diagnostic {
    std::string file;      // as given in the options; may be empty
    std::size_t line = 0;  // 1-based; 0 when the problem is the whole file
    Rule rule = Rule::syntax;
    std::string message;
    Severity severity = Severity::error;
};

// "Print_0001.mod:12: error: identifier 'x...' is 40 characters, at most 32 [identifier-length]"
std::string format(const Diagnostic& d);

bool has_errors(const std::vector<Diagnostic>& diagnostics);

// The error the throwing conveniences raise: the first error-severity diagnostic.
class RapidError : public std::runtime_error {
  public:
    explicit RapidError(Diagnostic d) : std::runtime_error(format(d)), diagnostic_(std::move(d)) {}

    const Diagnostic& diagnostic() const { return diagnostic_; }
    const std::string& file() const { return diagnostic_.file; }
    std::size_t line() const { return diagnostic_.line; }
    Rule rule() const { return diagnostic_.rule; }

  private:
    Diagnostic diagnostic_;
};

// Throws RapidError for the first error in `diagnostics`; warnings pass.
void throw_on_error(const std::vector<Diagnostic>& diagnostics);

}  // namespace fibrecell::drivers::abb::rapid
