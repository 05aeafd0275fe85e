#pragma once
// Compiled into every file of a service target that links nlohmann_json
// (cmake/extern_templates.cmake): the json type's member functions are instantiated once, in
// config/json_instance.cpp, instead of in each file that uses them (the queue component's files
// at -Og: 18.1 -> 15.3 s).
#include <nlohmann/json.hpp>

extern template class nlohmann::basic_json<>;
