#include "planner/io/text_fields.hpp"

#include "planner/io/number_parse.hpp"

namespace fibrecell::planner {

std::size_t split_fields(std::string_view line, char delimiter, std::string_view* fields,
                         std::size_t capacity) {
    std::size_t count = 0;
    for (;;) {
        const std::size_t end = line.find(delimiter);
        if (count < capacity) fields[count] = trim(line.substr(0, end));
        ++count;
        if (end == std::string_view::npos) return count;
        line.remove_prefix(end + 1);
    }
}

}  // namespace fibrecell::planner
