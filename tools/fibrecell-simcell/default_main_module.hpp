#pragma once
// The resident main module fibrecell-simcell loads unless --main-module says otherwise.

#include <string>

namespace fibrecell::simcell {

// FcMain.mod as installed (<prefix>/share/fibrecell/rapid, next to bin/), else in the source tree
// this program was built from.
std::string default_main_module();

}  // namespace fibrecell::simcell
