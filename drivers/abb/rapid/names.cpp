#include "drivers/abb/rapid/names.hpp"

#include <algorithm>
#include <cctype>
#include <iterator>
#include <utility>

namespace fibrecell::drivers::abb::rapid {
namespace {

// BossyMr/intellij-rapid RapidLexer.KEYWORDS, as listed in docs/rapid-subset.md ("Lexical
// elements"); lower case, sorted.
constexpr std::string_view reserved_words[] = {
    "alias",     "and",     "backward", "case",     "connect",   "const", "default",   "div",
    "do",        "else",    "elseif",   "endfor",   "endfunc",   "endif", "endmodule", "endproc",
    "endrecord", "endtest", "endtrap",  "endwhile", "error",     "exit",  "false",     "for",
    "from",      "func",    "goto",     "if",       "inout",     "local", "mod",       "module",
    "nostepin",  "not",     "noview",   "or",       "pers",      "proc",  "raise",     "readonly",
    "record",    "retry",   "return",   "step",     "sysmodule", "task",  "test",      "then",
    "to",        "trap",    "true",     "trynext",  "undo",      "var",   "viewonly",  "while",
    "with",      "xor"};

// Built-in functions with the type they return ("" = depends on the arguments or not needed).
constexpr std::pair<std::string_view, std::string_view> builtin_functions[] = {
    {"abs", "num"},
    {"acos", "num"},
    {"aoutput", "num"},
    {"argname", "string"},
    {"asin", "num"},
    {"atan", "num"},
    {"atan2", "num"},
    {"bitand", "num"},
    {"bitor", "num"},
    {"bitxor", "num"},
    {"bitneg", "num"},
    {"calcjointt", "jointtarget"},
    {"calcrobt", "robtarget"},
    {"cdate", "string"},
    {"cjointt", "jointtarget"},
    {"clkread", "num"},
    {"cos", "num"},
    {"cpos", "pos"},
    {"crobt", "robtarget"},
    {"ctime", "string"},
    {"ctool", "tooldata"},
    {"cwobj", "wobjdata"},
    {"dim", "num"},
    {"dinput", "num"},
    {"dnumtonum", "num"},
    {"doutput", "num"},
    {"eulerzyx", "num"},
    {"exp", "num"},
    {"ginput", "num"},
    {"ginputdnum", "dnum"},
    {"goutput", "num"},
    {"goutputdnum", "dnum"},
    {"gettime", "num"},
    {"isfile", "bool"},
    {"ispers", "bool"},
    {"isvar", "bool"},
    {"isstopmoveact", "bool"},
    {"modexist", "bool"},
    {"ainput", "num"},
    {"numtodnum", "dnum"},
    {"numtostr", "string"},
    {"dnumtostr", "string"},
    {"offs", "robtarget"},
    {"opmode", "num"},
    {"orientzyx", "orient"},
    {"orobt", "robtarget"},
    {"poseinv", "pose"},
    {"posemult", "pose"},
    {"posevect", "pos"},
    {"pow", "num"},
    {"present", "bool"},
    {"progmemfree", "num"},
    {"readnum", "num"},
    {"readstr", "string"},
    {"reltool", "robtarget"},
    {"round", "num"},
    {"runmode", "num"},
    {"sin", "num"},
    {"sqrt", "num"},
    {"strfind", "num"},
    {"strlen", "num"},
    {"strmap", "string"},
    {"strmatch", "num"},
    {"strmemb", "bool"},
    {"strorder", "bool"},
    {"strpart", "string"},
    {"strtobyte", "string"},
    {"strtoval", "bool"},
    {"tan", "num"},
    {"testdi", "bool"},
    {"trunc", "num"},
    {"valtostr", "string"},
    {"vectmagn", "num"},
};

// ASCII only (RAPID names are ASCII); std::tolower's locale lookup is measurable here.
char lower(char c) {
    return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c;
}

}  // namespace

std::string fold(std::string_view name) {
    std::string out(name);
    for (char& c : out) c = lower(c);
    return out;
}

bool same_name(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (lower(a[i]) != lower(b[i])) return false;
    return true;
}

bool is_identifier(std::string_view text) {
    if (text.empty() || !std::isalpha(static_cast<unsigned char>(text.front()))) return false;
    return std::all_of(text.begin(), text.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    });
}

bool is_reserved_word(std::string_view name) {
    if (name.size() < 2 || name.size() > 9) return false;  // "do" ... "endrecord"
    return std::any_of(std::begin(reserved_words), std::end(reserved_words),
                       [&](std::string_view w) { return same_name(w, name); });
}

bool is_builtin_function(std::string_view name) {
    const std::string key = fold(name);
    return std::any_of(std::begin(builtin_functions), std::end(builtin_functions),
                       [&](const auto& f) { return f.first == key; });
}

std::string_view builtin_function_type(std::string_view name) {
    const std::string key = fold(name);
    for (const auto& f : builtin_functions)
        if (f.first == key) return f.second;
    return {};
}

}  // namespace fibrecell::drivers::abb::rapid
