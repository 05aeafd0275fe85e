#include "drivers/abb/rapid/program.hpp"

#include "drivers/abb/rapid/names.hpp"

namespace fibrecell::drivers::abb::rapid {

std::string_view to_string(UnaryOp op) {
    switch (op) {
        case UnaryOp::minus:
            return "-";
        case UnaryOp::plus:
            return "+";
        case UnaryOp::logical_not:
            return "NOT";
    }
    return "?";
}

std::string_view to_string(BinaryOp op) {
    switch (op) {
        case BinaryOp::add:
            return "+";
        case BinaryOp::sub:
            return "-";
        case BinaryOp::mul:
            return "*";
        case BinaryOp::div:
            return "/";
        case BinaryOp::int_div:
            return "DIV";
        case BinaryOp::mod:
            return "MOD";
        case BinaryOp::eq:
            return "=";
        case BinaryOp::ne:
            return "<>";
        case BinaryOp::lt:
            return "<";
        case BinaryOp::gt:
            return ">";
        case BinaryOp::le:
            return "<=";
        case BinaryOp::ge:
            return ">=";
        case BinaryOp::logical_and:
            return "AND";
        case BinaryOp::logical_or:
            return "OR";
        case BinaryOp::logical_xor:
            return "XOR";
    }
    return "?";
}

std::string_view to_string(Storage s) {
    switch (s) {
        case Storage::var:
            return "VAR";
        case Storage::pers:
            return "PERS";
        case Storage::constant:
            return "CONST";
    }
    return "?";
}

std::string_view to_string(RoutineKind k) {
    switch (k) {
        case RoutineKind::proc:
            return "PROC";
        case RoutineKind::func:
            return "FUNC";
        case RoutineKind::trap:
            return "TRAP";
    }
    return "?";
}

std::vector<const Expr*> positional_args(const std::vector<Argument>& args) {
    std::vector<const Expr*> out;
    for (const Argument& a : args)
        if (a.positional() && a.value) out.push_back(&*a.value);
    return out;
}

const Argument* find_optional(const std::vector<Argument>& args, std::string_view name) {
    for (const Argument& a : args)
        if (!a.positional() && same_name(a.name, name)) return &a;
    return nullptr;
}

const DataDecl* Module::find_data(std::string_view data_name) const {
    for (const DataDecl& d : data)
        if (same_name(d.name, data_name)) return &d;
    return nullptr;
}

const Routine* Module::find_routine(std::string_view routine_name) const {
    for (const Routine& r : routines)
        if (same_name(r.name, routine_name)) return &r;
    return nullptr;
}

}  // namespace fibrecell::drivers::abb::rapid
