// Feeds the bytes as a RAPID module to the project's RAPID reader and validator
// (drivers/abb/rapid/reader.hpp), then a module that passes to the simulated task's loader
// (drivers/sim/rapid_exec, instantiate). Diagnostics and the loader's RuntimeError are the
// contract; any exception, crash or sanitizer report is a finding.
#include "drivers/abb/rapid/reader.hpp"
#include "drivers/sim/rapid_exec/task_data.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    namespace rapid = fibrecell::drivers::abb::rapid;
    namespace rapid_exec = fibrecell::drivers::sim::rapid_exec;
    const std::string_view text(reinterpret_cast<const char*>(data), size);

    rapid::ValidateOptions options;
    options.file_name = "FcChunk0001.mod";
    options.check_module_name = false;  // any module name, so mutations keep reaching the checks
    // The simulated cell's EIO signals, and those of the test modules (tests/data/rapid).
    options.known_signals = {"diFcPause",   "diFcAbort",       "diFcHeartbeat", "giFcRelease",
                             "doFcRunning", "doFcHeartbeat",   "goFcEvent",     "goFcBarrier",
                             "goEvent",     "diExtruderReady", "diJobReady",    "diAbort"};
    const rapid::CheckResult checked = rapid::check_module(text, options);
    if (!checked.module) return 0;
    rapid::move_targets(*checked.module);
    if (!checked.ok()) return 0;
    try {
        rapid_exec::instantiate(std::make_shared<const rapid::Module>(*checked.module), true,
                                "HOME:/fibrecell/job/FcChunk0001.mod");
    } catch (const rapid_exec::RuntimeError&) {
    }
    return 0;
}
