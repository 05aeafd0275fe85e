#include "drivers/abb/rapid/diagnostic.hpp"

namespace fibrecell::drivers::abb::rapid {

std::string_view to_string(Rule rule) {
    switch (rule) {
        case Rule::encoding:
            return "encoding";
        case Rule::line_ending:
            return "line-ending";
        case Rule::line_count:
            return "line-count";
        case Rule::syntax:
            return "syntax";
        case Rule::block:
            return "block";
        case Rule::nesting_depth:
            return "nesting-depth";
        case Rule::identifier_length:
            return "identifier-length";
        case Rule::string_length:
            return "string-length";
        case Rule::reserved_word:
            return "reserved-word";
        case Rule::builtin_name:
            return "builtin-name";
        case Rule::duplicate_name:
            return "duplicate-name";
        case Rule::module_count:
            return "module-count";
        case Rule::module_name:
            return "module-name";
        case Rule::module_attribute:
            return "module-attribute";
        case Rule::declaration_order:
            return "declaration-order";
        case Rule::declaration:
            return "declaration";
        case Rule::unknown_type:
            return "unknown-type";
        case Rule::undeclared:
            return "undeclared";
        case Rule::argument_count:
            return "argument-count";
        case Rule::optional_argument:
            return "optional-argument";
        case Rule::argument_type:
            return "argument-type";
        case Rule::aggregate_shape:
            return "aggregate-shape";
        case Rule::initializer:
            return "initializer";
        case Rule::const_assignment:
            return "const-assignment";
        case Rule::quaternion_norm:
            return "quaternion-norm";
        case Rule::quaternion_digits:
            return "quaternion-digits";
        case Rule::speed:
            return "speed";
        case Rule::tool_mass:
            return "tool-mass";
        case Rule::tool_cog:
            return "tool-cog";
        case Rule::trigger_setup:
            return "trigger-setup";
        case Rule::late_call:
            return "late-call";
    }
    return "unknown";
}

std::string format(const Diagnostic& d) {
    std::string out = d.file.empty() ? std::string("<rapid>") : d.file;
    if (d.line > 0) out += ":" + std::to_string(d.line);
    out += d.severity == Severity::error ? ": error: " : ": warning: ";
    out += d.message;
    out += " [";
    out += to_string(d.rule);
    out += "]";
    return out;
}

bool has_errors(const std::vector<Diagnostic>& diagnostics) {
    for (const Diagnostic& d : diagnostics)
        if (d.severity == Severity::error) return true;
    return false;
}

void throw_on_error(const std::vector<Diagnostic>& diagnostics) {
    for (const Diagnostic& d : diagnostics)
        if (d.severity == Severity::error) throw RapidError(d);
}

}  // namespace fibrecell::drivers::abb::rapid
