// The one instantiation of the json type's member functions that config/extern_json.hpp
// promises to every other file.
#include <nlohmann/json.hpp>

template class nlohmann::basic_json<>;
