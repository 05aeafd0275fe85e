// The source tree's path is compiled into this file alone (FIBRECELL_DEFAULT_MAIN_MODULE), so that
// main.cpp's object is the same in a clone elsewhere, for the compiler cache (docs/building.md).
#include "default_main_module.hpp"

#include <filesystem>
#include <system_error>

namespace fibrecell::simcell {

std::string default_main_module() {
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const auto installed = exe.parent_path().parent_path() / "share/fibrecell/rapid/FcMain.mod";
        if (std::filesystem::exists(installed, ec)) return installed.string();
    }
    return FIBRECELL_DEFAULT_MAIN_MODULE;
}

}  // namespace fibrecell::simcell
