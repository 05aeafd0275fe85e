#include "drivers/abb/rapid/reader.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>

namespace fibrecell::drivers::abb::rapid {

CheckResult check_module(std::string_view text, const ValidateOptions& options) {
    ParseResult parsed = parse_module(text, ParseOptions{options.file_name});
    CheckResult result{std::move(parsed.module), std::move(parsed.diagnostics)};
    if (result.module) {
        std::vector<Diagnostic> more = validate(*result.module, options);
        result.diagnostics.insert(result.diagnostics.end(), std::make_move_iterator(more.begin()),
                                  std::make_move_iterator(more.end()));
    }
    // In file order, so that the first error is the first one a reader of the file meets.
    std::stable_sort(result.diagnostics.begin(), result.diagnostics.end(),
                     [](const Diagnostic& a, const Diagnostic& b) { return a.line < b.line; });
    return result;
}

CheckResult check_module_file(const std::filesystem::path& path, ValidateOptions options) {
    if (options.file_name.empty()) options.file_name = path.filename().string();
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        CheckResult r;
        r.diagnostics.push_back(
            {options.file_name, 0, Rule::syntax, "cannot open '" + path.string() + "'"});
        return r;
    }
    std::ostringstream text;
    text << in.rdbuf();
    return check_module(text.str(), options);
}

Module read_module(std::string_view text, const ValidateOptions& options) {
    CheckResult r = check_module(text, options);
    throw_on_error(r.diagnostics);
    if (!r.module) throw RapidError({options.file_name, 0, Rule::syntax, "no module read"});
    return std::move(*r.module);
}

Module read_module_file(const std::filesystem::path& path, ValidateOptions options) {
    CheckResult r = check_module_file(path, std::move(options));
    throw_on_error(r.diagnostics);
    if (!r.module) throw RapidError({path.string(), 0, Rule::syntax, "no module read"});
    return std::move(*r.module);
}

}  // namespace fibrecell::drivers::abb::rapid
