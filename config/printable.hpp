#pragma once
// Text that came from a user (a job's name, a file name, a reason quoting them) made safe to log
// or to print on a terminal: control characters become visible escapes, so that a name holding
// "\n2026-12-02 ... info job.completed" cannot forge a log line and "\x1b[2K" cannot wipe one.
//
//   printable("bar\nfake")  == "bar\\nfake"
//   printable("\x1b[2K")    == "\\x1b[2K"
//
// Everything else, UTF-8 included, is kept as it is.

#include <string>
#include <string_view>

namespace fibrecell::config {

std::string printable(std::string_view text);

}  // namespace fibrecell::config
