#pragma once
// The error for a load case the static FEA cannot solve: the message says what is wrong with the
// set-up (which region, which part of the mesh) so the operator can fix it.

#include <stdexcept>
#include <string>

namespace fibrecell::planner {

class FeaError : public std::runtime_error {
  public:
    explicit FeaError(const std::string& problem) : std::runtime_error("FEA: " + problem) {}
};

}  // namespace fibrecell::planner
