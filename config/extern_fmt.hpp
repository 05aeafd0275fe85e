#pragma once
// Compiled into every file of a service target that logs (cmake/extern_templates.cmake): fmt 9
// (Debian 12's) compiles its formatting engine, detail::vformat_to<char> and the number writers
// it calls, into every file that formats, although libfmt exports it; this says it is there
// (the queue component's files at -Og: 18.1 -> 16.5 s). fmt 10 and later say so themselves.
#include <fmt/format.h>

#if FMT_VERSION >= 90000 && FMT_VERSION < 100000 && !defined(FMT_HEADER_ONLY)
FMT_BEGIN_NAMESPACE
namespace detail {
extern template FMT_API void vformat_to<char>(buffer<char>&, basic_string_view<char>,
                                              basic_format_args<FMT_BUFFER_CONTEXT(char)>,
                                              locale_ref);
}  // namespace detail
FMT_END_NAMESPACE
#endif
