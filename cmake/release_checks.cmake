# fibrecell_release_checks(NAME): a target NAME that builds everything `all` builds but the test
# programs that the sanitizer build (tools/setup.sh test) compiles the same way. Those compile at
# the same level there (-O0, the planner's at -O1: tests/CMakeLists.txt) with the same warnings
# as errors, so compiling them again in Release proves nothing new (with GCC 12, Debian 12's;
# GCC 13 and later also warn of values maybe uninitialized, and only without sanitizers). The
# libraries, programs and benchmarks compile at Release's own levels, where GCC's flow warnings
# differ, and the test programs with code for a build without sanitizers (the service tests' plan
# out of memory, the soak) compile here too. .ci/run builds NAME as its Release build
# (docs/building.md).
function(fibrecell_release_checks name)
    set(wanted "")
    fibrecell_collect_release_checks(${PROJECT_SOURCE_DIR} wanted)
    foreach(program IN ITEMS service_tests print_soak_test)
        if(TARGET ${program})
            list(APPEND wanted ${program})
        endif()
    endforeach()
    add_custom_target(${name})
    add_dependencies(${name} ${wanted})
endfunction()

# Appends to OUT_VAR the targets made in DIR and below that `all` builds, but those under tests/.
function(fibrecell_collect_release_checks dir out_var)
    set(found ${${out_var}})
    fibrecell_targets_under(${dir} targets)
    foreach(target IN LISTS targets)
        get_target_property(src_dir ${target} SOURCE_DIR)
        file(RELATIVE_PATH rel ${PROJECT_SOURCE_DIR} ${src_dir})
        get_target_property(type ${target} TYPE)
        get_target_property(excluded ${target} EXCLUDE_FROM_ALL)
        if(NOT rel MATCHES "^tests(/|$)" AND NOT type STREQUAL "INTERFACE_LIBRARY" AND NOT excluded)
            list(APPEND found ${target})
        endif()
    endforeach()
    set(${out_var} ${found} PARENT_SCOPE)
endfunction()
