# Writes OUT, the build's name for itself (config/build_info.hpp): the project's VERSION and the
# commit the sources are at (`git describe --always --dirty`, "unknown" outside a git checkout).
# Run at every build; OUT changes (and its one translation unit compiles again) only when the
# commit does.
#   cmake -DSOURCE_DIR=... -DVERSION=... -DOUT=... -P write_build_info.cmake
set(commit "unknown")
find_program(GIT git)
if(GIT AND EXISTS "${SOURCE_DIR}/.git")
    execute_process(COMMAND "${GIT}" -C "${SOURCE_DIR}" describe --always --dirty --abbrev=12
                    OUTPUT_VARIABLE described OUTPUT_STRIP_TRAILING_WHITESPACE
                    RESULT_VARIABLE failed ERROR_QUIET)
    if(NOT failed AND described)
        set(commit "${described}")
    endif()
endif()
set(text "// Written by cmake/write_build_info.cmake at build time: do not edit.
#include \"config/build_info.hpp\"

namespace fibrecell::config {
const char* build_version() { return \"${VERSION}\"; }
const char* build_commit() { return \"${commit}\"; }
}  // namespace fibrecell::config
")
if(EXISTS "${OUT}")
    file(READ "${OUT}" old)
endif()
if(NOT "${old}" STREQUAL "${text}")
    file(WRITE "${OUT}" "${text}")
endif()
