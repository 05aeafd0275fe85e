#pragma once
// Starts `program` with `args` (argv[0] added) and the file actions the caller set up (which
// descriptors the child gets); returns its pid, or -1 when it cannot be started (the caller
// cleans up its descriptors, then says so).

#include <string>
#include <vector>

#include <spawn.h>
#include <sys/types.h>

extern char** environ;

namespace fibrecell::test {

inline pid_t spawn_program(const std::string& program, std::vector<std::string> args,
                           const posix_spawn_file_actions_t& actions) {
    args.insert(args.begin(), program);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = -1;
    if (posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ) != 0) return -1;
    return pid;
}

}  // namespace fibrecell::test
