#pragma once
// The task's data: module data as loaded (one Variable per declaration), routine frames with
// their local data and parameters, and the slots (places a value lives) that names, components
// and indices resolve to. No thread, no I/O: the executor owns one TaskData under its lock.

#include "drivers/abb/rapid/program.hpp"
#include "drivers/abb/rapid/value.hpp"

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace fibrecell::drivers::sim::rapid_exec {

namespace rapid = abb::rapid;

// A run-time error of the program at `line` of the module being executed (the controller would
// raise ERR_... there). The executor adds the module name.
class RuntimeError : public std::runtime_error {
  public:
    RuntimeError(std::size_t line, const std::string& message)
        : std::runtime_error(message), line_(line) {}
    std::size_t line() const { return line_; }

  private:
    std::size_t line_;
};

struct Variable {
    std::string name;  // as declared
    std::string type;  // canonical ("num"); the element type of an array
    rapid::Storage storage = rapid::Storage::var;
    bool local = false;     // LOCAL module data: not seen from other modules
    bool read_only = false;  // CONST, FOR variable
    std::vector<std::size_t> extents;  // array sizes; empty for a scalar
    rapid::Value value;
    rapid::Value initial;  // what reset_pp() restores (VAR, CONST)
};

// A module in the task, with its data. Held by shared_ptr so that a frame still executing in a
// module keeps it alive when the program unloads it.
struct LoadedModule {
    std::shared_ptr<const rapid::Module> module;
    std::map<std::string, Variable> data;  // by folded name
    bool dynamic = false;  // loaded by the program (StartLoad/Load): unloaded by reset_pp()
    std::string path;      // file it was loaded from ("" when loaded by the controller)

    const std::string& name() const { return module->name; }
};

// An instruction's positional arguments must be `n`: else "MoveL expects 4 arguments, found 3".
void expect_args(const std::vector<const rapid::Expr*>& args, std::size_t n, const std::string& name,
                 std::size_t line);

// The first value of declaration `d` whose type and extents `v` holds: the value the reader
// evaluated, the initialiser evaluated by `eval` and fitted to them, or the type's default.
// Throws RuntimeError at the declaration's line.
rapid::Value initial_value(const rapid::DataDecl& d, const Variable& v,
                           const std::function<rapid::Value(const rapid::Expr&)>& eval);

// Builds the module's data from its declarations (initial values as the reader evaluated them,
// or evaluated now against earlier data of the module). Throws RuntimeError.
std::shared_ptr<LoadedModule> instantiate(std::shared_ptr<const rapid::Module> module,
                                          bool dynamic, std::string path);

// Where a value lives: a whole variable, a record component or an array element.
struct Slot {
    rapid::Value* value = nullptr;
    std::string type;                  // declared type of what the slot holds
    std::vector<std::size_t> extents;  // remaining array dimensions
    bool read_only = false;
    std::string what;  // the name, for messages
};

// One routine call: its module, its data, its parameters and the line being executed.
struct Frame {
    std::shared_ptr<LoadedModule> module;
    const rapid::Routine* routine = nullptr;
    std::map<std::string, Variable> locals;  // routine data, IN parameters, FOR variables
    std::map<std::string, Slot> refs;        // VAR/PERS/INOUT parameters: the caller's slots
    std::vector<std::string> absent;         // optional parameters not passed (folded)
    std::size_t line = 0;
};

// Stores `value` in `slot` after fitting it to the slot's type; throws RuntimeError at `line`.
void assign(const Slot& slot, const rapid::Value& value, std::size_t line);

// `variable` as a slot.
Slot slot_of(Variable& variable);

// The slot of a record component or array element of `base`; throws RuntimeError.
Slot component_slot(const Slot& base, const std::string& component, std::size_t line);
Slot element_slot(const Slot& base, const rapid::Value& index, std::size_t line);

}  // namespace fibrecell::drivers::sim::rapid_exec
