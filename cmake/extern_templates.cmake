# fibrecell_extern_templates(DIR): the heavy templates that nearly every file of the service
# instantiates for itself, instantiated once. Every target of daemon/ and drivers/ that links
# nlohmann_json compiles its files with config/extern_json.hpp included first and links
# fibrecell_json (the one instantiation); one that logs (spdlog, or our config library, which
# passes spdlog on) with config/extern_fmt.hpp (libfmt has the instantiation). A forced include,
# not an #include in each file: a file that includes the library directly, as it always did,
# gains it too. The service's 33 files and batches at -Og with the sanitizers: 513 -> 450 CPU
# seconds. Not the planner's or the tests' targets: they log little, and fmt's header forced into
# a planner batch cost more than it saved (docs/building.md).
function(fibrecell_extern_templates root)
    fibrecell_targets_under(${root} targets)
    foreach(target IN LISTS targets)
        get_target_property(type ${target} TYPE)
        if(NOT type MATCHES "^(STATIC_LIBRARY|EXECUTABLE)$" OR target STREQUAL "fibrecell_json")
            continue()
        endif()
        # The service's side only: the planner and the tests log little (measured: fmt's header
        # forced into a planner batch cost more than it saved).
        get_target_property(src_dir ${target} SOURCE_DIR)
        file(RELATIVE_PATH rel ${PROJECT_SOURCE_DIR} ${src_dir})
        if(NOT rel MATCHES "^(daemon|drivers)(/|$)")
            continue()
        endif()
        get_target_property(links ${target} LINK_LIBRARIES)
        if(NOT links)
            continue()
        endif()
        if("nlohmann_json::nlohmann_json" IN_LIST links)
            target_compile_options(${target} PRIVATE
                "SHELL:-include ${PROJECT_SOURCE_DIR}/config/extern_json.hpp")
            target_link_libraries(${target} PRIVATE fibrecell_json)
        endif()
        if("spdlog::spdlog" IN_LIST links OR "fibrecell_config" IN_LIST links)
            target_compile_options(${target} PRIVATE
                "SHELL:-include ${PROJECT_SOURCE_DIR}/config/extern_fmt.hpp")
        endif()
    endforeach()
endfunction()
