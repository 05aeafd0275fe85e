#pragma once
// The one error type for bad input files: names the file, the line or element, and the problem.

#include <cstddef>
#include <stdexcept>
#include <string>

namespace fibrecell::planner {

class InputError : public std::runtime_error {
  public:
    // `where` is "line 12", "element 345", "vertex 7" or empty when the problem is the whole file.
    InputError(const std::string& file, const std::string& where, const std::string& problem)
        : std::runtime_error(file + (where.empty() ? "" : ": " + where) + ": " + problem),
          file_(file) {}

    static InputError at_line(const std::string& file, std::size_t line,
                              const std::string& problem) {
        return InputError(file, "line " + std::to_string(line), problem);
    }
    static InputError at_element(const std::string& file, std::size_t element,
                                 const std::string& problem) {
        return InputError(file, "element " + std::to_string(element), problem);
    }

    const std::string& file() const { return file_; }

  private:
    std::string file_;
};

}  // namespace fibrecell::planner
