#pragma once
// The program model the reader produces and a simulated controller executes: a module holds data
// declarations and routines; routines hold local declarations and statements; statements and
// expressions are variant trees. Every node keeps its 1-based source line. Names are kept as
// written; compare them with same_name() (RAPID is case-insensitive).

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "drivers/abb/rapid/value.hpp"

namespace fibrecell::drivers::abb::rapid {

// A heap-held child with value semantics, so that trees copy like values.
template <class T>
class Box {
  public:
    Box(T value) : p_(std::make_unique<T>(std::move(value))) {}  // NOLINT: implicit on purpose
    Box(const Box& other) : p_(std::make_unique<T>(*other)) {}
    Box(Box&&) noexcept = default;
    Box& operator=(const Box& other) {
        if (this != &other) p_ = std::make_unique<T>(*other);
        return *this;
    }
    Box& operator=(Box&&) noexcept = default;
    ~Box() = default;

    T& operator*() { return *p_; }
    const T& operator*() const { return *p_; }
    T* operator->() { return p_.get(); }
    const T* operator->() const { return p_.get(); }

  private:
    std::unique_ptr<T> p_;
};

// ---- Expressions -------------------------------------------------------------------------------

enum class UnaryOp { minus, plus, logical_not };
enum class BinaryOp {
    add,
    sub,
    mul,
    div,
    int_div,
    mod,  // + - * / DIV MOD
    eq,
    ne,
    lt,
    gt,
    le,
    ge,  // = <> < > <= >=
    logical_and,
    logical_or,
    logical_xor,
};
std::string_view to_string(UnaryOp op);
std::string_view to_string(BinaryOp op);

struct Expr;
struct Argument;

struct Literal {
    std::variant<double, bool, std::string> value;
    std::string text;  // a number as written ("0.707107", "9E9"): the validator counts decimals
};
struct NameRef {
    std::string name;
};
struct Aggregate {  // [a, b, ...]
    std::vector<Expr> items;
};
struct ComponentAccess {  // base.component
    Box<Expr> base;
    std::string component;
};
struct IndexAccess {  // base{i, j}; 1-based
    Box<Expr> base;
    std::vector<Expr> indices;
};
struct Unary {
    UnaryOp op;
    Box<Expr> operand;
};
struct Binary {
    BinaryOp op;
    Box<Expr> lhs;
    Box<Expr> rhs;
};
struct FunctionCall {  // Offs(p, 0, 0, 10), Round(x \Dec:=2)
    std::string name;
    std::vector<Argument> args;
};

struct Expr {
    std::variant<Literal, NameRef, Aggregate, ComponentAccess, IndexAccess, Unary, Binary,
                 FunctionCall>
        node;
    std::size_t line = 0;
};

// One argument of an instruction, procedure or function call, in source order: positional
// (`name` empty), optional `\Name:=value`, or switch `\Name` (no value).
struct Argument {
    std::string name;
    std::optional<Expr> value;
    std::size_t line = 0;

    bool positional() const { return name.empty(); }
    bool is_switch() const { return !name.empty() && !value; }
};

// The positional arguments in order.
std::vector<const Expr*> positional_args(const std::vector<Argument>& args);
// The optional argument or switch called `name` (case-insensitive); nullptr when absent.
const Argument* find_optional(const std::vector<Argument>& args, std::string_view name);

// ---- Statements --------------------------------------------------------------------------------

struct Statement;
using Block = std::vector<Statement>;

struct ProcCall {  // MoveL p, v100, z0, tool0 \WObj:=wobj0;   Incr n;   MyProc;
    std::string name;
    std::vector<Argument> args;
};
struct LateCall {  // %"Print_0001:Print_0001"%;  or  %proc_name%;
    Expr routine;  // string expression naming "[module:]routine"
    std::vector<Argument> args;
};
struct Assign {  // target := value;  target is a NameRef, ComponentAccess or IndexAccess
    Expr target;
    Expr value;
};
struct IfBranch {
    Expr condition;
    Block body;
    std::size_t line = 0;
};
struct If {  // IF .. THEN .. {ELSEIF .. THEN ..} [ELSE ..] ENDIF, or the one-statement form
    std::vector<IfBranch> branches;  // IF, then each ELSEIF
    Block else_body;
};
struct While {
    Expr condition;
    Block body;
};
struct For {  // FOR i FROM a TO b [STEP c] DO .. ENDFOR; `variable` is declared by the loop
    std::string variable;
    Expr from;
    Expr to;
    std::optional<Expr> step;
    Block body;
};
struct TestCase {
    std::vector<Expr> values;  // CASE a, b:
    Block body;
    std::size_t line = 0;
};
struct TestStatement {  // TEST subject CASE .. DEFAULT: .. ENDTEST
    Expr subject;
    std::vector<TestCase> cases;
    bool has_default = false;
    Block default_body;
};
struct Return {
    std::optional<Expr> value;  // FUNC only
};
struct Exit {};
struct Connect {  // CONNECT intno WITH trap_routine;
    Expr interrupt;
    std::string trap;
};

struct Statement {
    std::variant<ProcCall, LateCall, Assign, If, While, For, TestStatement, Return, Exit, Connect>
        node;
    std::size_t line = 0;
};

// ---- Declarations, routines, module ------------------------------------------------------------

enum class Storage { var, pers, constant };
enum class Visibility { global, local, task };  // task: TASK PERS
std::string_view to_string(Storage s);

struct DataDecl {
    Visibility visibility = Visibility::global;
    Storage storage = Storage::var;
    std::string type;  // as written ("robtarget")
    std::string name;
    std::vector<Expr> dims;            // {10} or {2, 3}; empty for a scalar
    std::vector<std::size_t> extents;  // dims evaluated (empty when not constant or scalar)
    std::optional<Expr> init;          // := expression
    // The initial value, conform()ed to the type: the evaluated initialiser, or the type's default
    // when there is none. Empty when the initialiser is not a constant the reader can evaluate.
    std::optional<Value> value;
    std::size_t line = 0;
};

enum class ParamAccess { in, var, pers, inout };
struct Param {
    ParamAccess access = ParamAccess::in;
    bool optional = false;  // \name
    std::string type;       // "switch" for an optional switch parameter
    std::string name;
    std::size_t array_dims = 0;  // {*} or {*,*}
    std::size_t line = 0;
};

enum class RoutineKind { proc, func, trap };
std::string_view to_string(RoutineKind k);

struct Routine {
    RoutineKind kind = RoutineKind::proc;
    bool local = false;  // LOCAL PROC
    std::string name;
    std::string return_type;  // FUNC only
    std::vector<Param> params;
    std::vector<DataDecl> locals;
    Block body;
    std::size_t line = 0;      // of PROC/FUNC/TRAP
    std::size_t end_line = 0;  // of ENDPROC/ENDFUNC/ENDTRAP
};

struct Module {
    std::string name;
    std::vector<std::string> attributes;  // SYSMODULE, NOSTEPIN, ... as written
    std::vector<std::string> header;      // lines of the %%% block, trimmed ("VERSION:1")
    std::vector<DataDecl> data;
    std::vector<Routine> routines;
    std::string file;            // as given to the reader; may be empty
    std::size_t line = 0;        // of MODULE
    std::size_t end_line = 0;    // of ENDMODULE
    std::size_t line_count = 0;  // lines in the source text

    const DataDecl* find_data(std::string_view data_name) const;
    const Routine* find_routine(std::string_view routine_name) const;
};

}  // namespace fibrecell::drivers::abb::rapid
