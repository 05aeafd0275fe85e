// Module-level rules (line count, module name, attributes, unique names) and the walk order.

#include <filesystem>
#include <map>

#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/validate_detail.hpp"

namespace fibrecell::drivers::abb::rapid {
namespace detail {
namespace {

constexpr std::string_view attribute_names[] = {"SYSMODULE", "NOVIEW", "NOSTEPIN", "VIEWONLY",
                                                "READONLY"};

bool has(const std::vector<std::string>& list, std::string_view name) {
    for (const std::string& s : list)
        if (same_name(s, name)) return true;
    return false;
}

}  // namespace

Checker::Checker(const Module& module, const ValidateOptions& options, std::vector<Diagnostic>& out)
    : module_(module),
      options_(options),
      out_(out),
      file_(options.file_name.empty() ? module.file : options.file_name) {}

void Checker::report(Rule rule, std::size_t line, std::string message, Severity severity) {
    out_.push_back({file_, line, rule, std::move(message), severity});
}

void Checker::run() {
    const Module& m = module_;
    if (m.line_count > options_.max_lines)
        report(Rule::line_count, options_.max_lines + 1,
               "module has " + std::to_string(m.line_count) + " lines; at most " +
                   std::to_string(options_.max_lines) + " per file");

    if (options_.check_module_name && !options_.file_name.empty()) {
        const std::string stem = std::filesystem::path(options_.file_name).stem().string();
        if (!same_name(stem, m.name))
            report(Rule::module_name, m.line,
                   "module " + m.name + " is in file '" + options_.file_name +
                       "'; the module name must equal the file name (" + stem + ")");
    }
    if (has(options_.loaded_modules, m.name))
        report(Rule::module_name, m.line,
               "a module named " + m.name + " is already loaded in the task");

    // Attributes: known, not repeated, not mutually exclusive (intellij-rapid Attribute rules).
    std::vector<std::string> seen;
    for (const std::string& a : m.attributes) {
        bool known = false;
        for (std::string_view n : attribute_names) known = known || same_name(a, n);
        if (!known)
            report(Rule::module_attribute, m.line, "unknown module attribute '" + a + "'");
        else if (has(seen, a))
            report(Rule::module_attribute, m.line, "attribute " + a + " repeated");
        seen.push_back(a);
    }
    auto exclusive = [&](std::string_view a, std::string_view b) {
        if (has(seen, a) && has(seen, b))
            report(Rule::module_attribute, m.line,
                   std::string(a) + " and " + std::string(b) + " exclude each other");
    };
    exclusive("NOVIEW", "NOSTEPIN");
    exclusive("NOVIEW", "VIEWONLY");
    exclusive("NOVIEW", "READONLY");
    exclusive("VIEWONLY", "READONLY");

    // Module-scope names: data and routines share one namespace.
    std::map<std::string, std::size_t> first_line;
    auto unique = [&](const std::string& name, std::size_t line) {
        const auto [it, fresh] = first_line.emplace(fold(name), line);
        if (!fresh)
            report(Rule::duplicate_name, line,
                   "'" + name + "' is already declared on line " + std::to_string(it->second));
    };
    for (const DataDecl& d : m.data) unique(d.name, d.line);
    for (const Routine& r : m.routines) {
        unique(r.name, r.line);
        check_declared_name(r.name, r.line, "a routine");
    }

    check_declarations(m.data, true);
    visible_module_data_ = m.data.size();
    for (const Routine& r : m.routines) {
        routine_ = &r;
        visible_locals_ = 0;
        loop_variables_.clear();
        check_params(r);
        check_declarations(r.locals, false);
        visible_locals_ = r.locals.size();
        check_block(r.body);
        check_triggers(r);
    }
    routine_ = nullptr;
}

const Expr* positional(const std::vector<Argument>& args, std::size_t n) {
    std::size_t i = 0;
    for (const Argument& a : args) {
        if (!a.positional() || !a.value) continue;
        if (i++ == n) return &*a.value;
    }
    return nullptr;
}

const Expr* aggregate_item(const Expr* e, std::initializer_list<std::size_t> path) {
    for (std::size_t i : path) {
        if (e == nullptr) return nullptr;
        const auto* a = std::get_if<Aggregate>(&e->node);
        if (a == nullptr || i >= a->items.size()) return nullptr;
        e = &a->items[i];
    }
    return e;
}

}  // namespace detail

std::vector<Diagnostic> validate(const Module& module, const ValidateOptions& options) {
    std::vector<Diagnostic> out;
    detail::Checker(module, options, out).run();
    return out;
}

}  // namespace fibrecell::drivers::abb::rapid
