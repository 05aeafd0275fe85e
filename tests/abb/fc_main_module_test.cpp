// The resident RAPID main module shipped in drivers/abb/rapid/FcMain.mod, read with the project's
// RAPID reader: it validates cleanly with the configured signals, exposes main and FcBarrier to
// the chunks, connects and arms its interrupts, loads chunks in the order StartLoad \Dynamic ->
// WaitLoad -> late-bound call -> UnLoad, and names chunks as the chunk writer does.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "drivers/abb/rapid/reader.hpp"
#include "tests/support/project_paths.hpp"

using namespace fibrecell::drivers::abb::rapid;

namespace {

const std::string module_path = fibrecell::test::source_path("drivers/abb/rapid/FcMain.mod");

// The signals of docs/irc5-setup.md (cell YAML defaults).
const std::vector<std::string> fc_signals = {"diFcPause",   "diFcAbort",   "diFcHeartbeat",
                                             "giFcRelease", "doFcRunning", "doFcHeartbeat",
                                             "goFcEvent",   "goFcBarrier"};

ValidateOptions main_options() {
    ValidateOptions o;
    o.known_signals = fc_signals;
    return o;
}

std::string all(const std::vector<Diagnostic>& ds) {
    std::string out;
    for (const Diagnostic& d : ds) out += "  " + format(d) + "\n";
    return out;
}

// The module as read; any diagnostic is a failure.
const Module& fc_main() {
    static const Module m = [] {
        const CheckResult r = check_module_file(module_path, main_options());
        for (const Diagnostic& d : r.diagnostics) throw RapidError(d);
        if (!r.module) throw std::runtime_error("FcMain.mod did not parse");
        return *r.module;
    }();
    return m;
}

const Routine& routine(std::string_view name) {
    const Routine* r = fc_main().find_routine(name);
    if (r == nullptr) throw std::runtime_error("FcMain has no routine " + std::string(name));
    return *r;
}

// ---- Walking the statement model ----------------------------------------------------------------

// Every statement of `block` in source order, nested blocks included (pre-order).
void walk(const Block& block, std::vector<const Statement*>& out) {
    for (const Statement& s : block) {
        out.push_back(&s);
        std::visit(
            [&](const auto& n) {
                using T = std::decay_t<decltype(n)>;
                if constexpr (std::is_same_v<T, If>) {
                    for (const IfBranch& b : n.branches) walk(b.body, out);
                    walk(n.else_body, out);
                } else if constexpr (std::is_same_v<T, While> || std::is_same_v<T, For>) {
                    walk(n.body, out);
                } else if constexpr (std::is_same_v<T, TestStatement>) {
                    for (const TestCase& c : n.cases) walk(c.body, out);
                    walk(n.default_body, out);
                }
            },
            s.node);
    }
}

std::vector<const Statement*> statements_of(const Routine& r) {
    std::vector<const Statement*> out;
    walk(r.body, out);
    return out;
}

// The same walk, with calls to the module's own PROCs replaced by their bodies (each routine is
// expanded once per path, so recursion cannot loop).
void expand(const Module& m, const Block& block, std::vector<std::string>& stack,
            std::vector<const Statement*>& out) {
    std::vector<const Statement*> flat;
    walk(block, flat);
    for (const Statement* s : flat) {
        out.push_back(s);
        const auto* call = std::get_if<ProcCall>(&s->node);
        if (call == nullptr) continue;
        const Routine* r = m.find_routine(call->name);
        if (r == nullptr || r->kind != RoutineKind::proc) continue;
        if (std::any_of(stack.begin(), stack.end(),
                        [&](const std::string& n) { return same_name(n, r->name); }))
            continue;
        stack.push_back(r->name);
        expand(m, r->body, stack, out);
        stack.pop_back();
    }
}

std::vector<const Statement*> expanded(const Routine& r) {
    std::vector<std::string> stack{r.name};
    std::vector<const Statement*> out;
    expand(fc_main(), r.body, stack, out);
    return out;
}

const ProcCall* as_call(const Statement* s, std::string_view name = {}) {
    const auto* c = std::get_if<ProcCall>(&s->node);
    if (c == nullptr || (!name.empty() && !same_name(c->name, name))) return nullptr;
    return c;
}

// Index of the first call to `name` at or after `from` in `seq`; seq.size() when none.
std::size_t find_call(const std::vector<const Statement*>& seq, std::string_view name,
                      std::size_t from = 0) {
    for (std::size_t i = from; i < seq.size(); ++i)
        if (as_call(seq[i], name) != nullptr) return i;
    return seq.size();
}

std::size_t count_calls(const std::vector<const Statement*>& seq, std::string_view name) {
    return static_cast<std::size_t>(std::count_if(
        seq.begin(), seq.end(), [&](const Statement* s) { return as_call(s, name) != nullptr; }));
}

// The name a plain name expression refers to ("" for anything else).
std::string name_of(const Expr* e) {
    if (e == nullptr) return {};
    const auto* n = std::get_if<NameRef>(&e->node);
    return n == nullptr ? std::string() : n->name;
}

std::optional<double> num_of(const Expr* e) {
    if (e == nullptr) return std::nullopt;
    const auto* l = std::get_if<Literal>(&e->node);
    if (l == nullptr || !std::holds_alternative<double>(l->value)) return std::nullopt;
    return std::get<double>(l->value);
}

const Expr* arg(const ProcCall& c, std::size_t i) {
    const std::vector<const Expr*> p = positional_args(c.args);
    return i < p.size() ? p[i] : nullptr;
}

// Whether `e` mentions the name or calls the function `name` anywhere.
bool mentions(const Expr& e, std::string_view name) {
    return std::visit(
        [&](const auto& n) -> bool {
            using T = std::decay_t<decltype(n)>;
            if constexpr (std::is_same_v<T, NameRef>) {
                return same_name(n.name, name);
            } else if constexpr (std::is_same_v<T, Aggregate>) {
                return std::any_of(n.items.begin(), n.items.end(),
                                   [&](const Expr& i) { return mentions(i, name); });
            } else if constexpr (std::is_same_v<T, ComponentAccess>) {
                return mentions(*n.base, name);
            } else if constexpr (std::is_same_v<T, IndexAccess>) {
                return mentions(*n.base, name);
            } else if constexpr (std::is_same_v<T, Unary>) {
                return mentions(*n.operand, name);
            } else if constexpr (std::is_same_v<T, Binary>) {
                return mentions(*n.lhs, name) || mentions(*n.rhs, name);
            } else if constexpr (std::is_same_v<T, FunctionCall>) {
                if (same_name(n.name, name)) return true;
                return std::any_of(n.args.begin(), n.args.end(), [&](const Argument& a) {
                    return a.value && mentions(*a.value, name);
                });
            } else {
                return false;
            }
        },
        e.node);
}

// ---- A tiny interpreter for the module's string FUNCs (assignments, IF, WHILE, RETURN) -------

class FuncRunner {
  public:
    explicit FuncRunner(const Module& m) : m_(m) {
        for (const DataDecl& d : m.data)
            if (d.value) globals_[fold(d.name)] = *d.value;
    }

    void set(std::string_view name, Value v) { globals_.at(fold(name)) = std::move(v); }

    Value call(std::string_view name, std::vector<Value> args) {
        const Routine* r = m_.find_routine(name);
        if (r == nullptr || r->kind != RoutineKind::func)
            throw std::runtime_error("no FUNC " + std::string(name));
        if (args.size() != r->params.size())
            throw std::runtime_error("wrong argument count for " + std::string(name));
        Frame frame;
        for (std::size_t i = 0; i < args.size(); ++i)
            frame[fold(r->params[i].name)] = std::move(args[i]);
        for (const DataDecl& d : r->locals) frame[fold(d.name)] = d.value.value_or(Value{});
        std::optional<Value> result = run(r->body, frame);
        if (!result) throw std::runtime_error("FUNC " + r->name + " ended without RETURN");
        return *result;
    }

  private:
    using Frame = std::map<std::string, Value>;

    Value eval(const Expr& e, Frame& frame) {
        EvalContext c;
        c.lookup = [this, &frame](std::string_view n) -> const Value* {
            const std::string key = fold(n);
            if (auto it = frame.find(key); it != frame.end()) return &it->second;
            if (auto it = globals_.find(key); it != globals_.end()) return &it->second;
            return nullptr;
        };
        c.call = [this, &frame](const FunctionCall& f, std::size_t) -> std::optional<Value> {
            const Routine* r = m_.find_routine(f.name);
            if (r == nullptr || r->kind != RoutineKind::func) return std::nullopt;
            std::vector<Value> args;
            for (const Expr* a : positional_args(f.args)) args.push_back(eval(*a, frame));
            return call(f.name, std::move(args));
        };
        return evaluate(e, c);
    }

    std::optional<Value> run(const Block& block, Frame& frame) {
        for (const Statement& s : block) {
            if (const auto* a = std::get_if<Assign>(&s.node)) {
                const auto& target = std::get<NameRef>(a->target.node);
                frame.at(fold(target.name)) = eval(a->value, frame);
            } else if (const auto* w = std::get_if<While>(&s.node)) {
                for (int guard = 0; eval(w->condition, frame).boolean(); ++guard) {
                    if (guard > 1000) throw std::runtime_error("WHILE does not end");
                    if (auto r = run(w->body, frame)) return r;
                }
            } else if (const auto* i = std::get_if<If>(&s.node)) {
                const Block* taken = &i->else_body;
                for (const IfBranch& b : i->branches)
                    if (eval(b.condition, frame).boolean()) {
                        taken = &b.body;
                        break;
                    }
                if (auto r = run(*taken, frame)) return r;
            } else if (const auto* ret = std::get_if<Return>(&s.node)) {
                return eval(*ret->value, frame);
            } else {
                throw std::runtime_error("statement on line " + std::to_string(s.line) +
                                         " is outside this test's interpreter");
            }
        }
        return std::nullopt;
    }

    const Module& m_;
    std::map<std::string, Value> globals_;
};

// A chunk as the chunk writer emits it (simplified): one event trigger, a barrier.
std::string chunk_text(std::string_view name, std::string_view barrier_call) {
    const std::string target =
        "[[350,0,200],[0.000000,0.000000,1.000000,0.000000],[0,0,0,0],"
        "[9E9,9E9,9E9,9E9,9E9,9E9]]";
    std::string t = "MODULE " + std::string(name) + "\n";
    t += "  LOCAL VAR triggdata tgEvent;\n";
    t += "  PROC " + std::string(name) + "()\n";
    t += "    TriggIO tgEvent, 0 \\Start \\GOp:=goFcEvent, 41;\n";
    t += "    MoveL " + target + ", v100, fine, tool0;\n";
    t += "    " + std::string(barrier_call) + "\n";
    t += "    TriggL " + target + ", v100, tgEvent, fine, tool0;\n";
    t += "  ENDPROC\nENDMODULE\n";
    return t;
}

}  // namespace

TEST(FcMainModule, ValidatesWithoutDiagnostics) {
    const CheckResult r = check_module_file(module_path, main_options());
    ASSERT_TRUE(r.module.has_value()) << all(r.diagnostics);
    EXPECT_TRUE(r.diagnostics.empty()) << all(r.diagnostics);
    EXPECT_EQ(r.module->name, "FcMain");
    EXPECT_LT(r.module->line_count, 1000u);
}

TEST(FcMainModule, UsesExactlyTheDocumentedSignals) {
    // Without the I/O configuration every signal is undeclared, and nothing else is.
    const CheckResult r = check_module_file(module_path);
    std::set<std::string> used;
    for (const Diagnostic& d : r.diagnostics) {
        ASSERT_EQ(d.rule, Rule::undeclared) << format(d);
        const auto open = d.message.find('\'');
        const auto close = d.message.find('\'', open + 1);
        ASSERT_NE(close, std::string::npos) << format(d);
        EXPECT_NE(d.message.find("is not declared"), std::string::npos) << format(d);
        used.insert(d.message.substr(open + 1, close - open - 1));
    }
    EXPECT_EQ(used, std::set<std::string>(fc_signals.begin(), fc_signals.end()));
}

TEST(FcMainModule, ExposesMainAndFcBarrierOnly) {
    const Routine& main = routine("main");
    EXPECT_EQ(main.kind, RoutineKind::proc);
    EXPECT_TRUE(main.params.empty());
    EXPECT_FALSE(main.local);

    const Routine& barrier = routine("FcBarrier");
    EXPECT_EQ(barrier.name, "FcBarrier");
    EXPECT_EQ(barrier.kind, RoutineKind::proc);
    EXPECT_FALSE(barrier.local);
    ASSERT_EQ(barrier.params.size(), 1u);
    EXPECT_EQ(barrier.params[0].type, "num");
    EXPECT_EQ(barrier.params[0].access, ParamAccess::in);
    EXPECT_FALSE(barrier.params[0].optional);
    EXPECT_EQ(barrier.params[0].array_dims, 0u);

    // Everything else is LOCAL, so that no chunk name can clash with it.
    std::set<std::string> global;
    for (const Routine& r : fc_main().routines)
        if (!r.local) global.insert(r.name);
    EXPECT_EQ(global, (std::set<std::string>{"main", "FcBarrier"}));
}

TEST(FcMainModule, DeclaresTheJobParametersAndStatusAsGlobalPers) {
    struct Expected {
        std::string name, type;
        Value initial;
    };
    const std::vector<Expected> expected = {
        {"sFcJobDir", "string", string_value("HOME:/fibrecell/job")},
        {"nFcChunkCount", "num", num_value(0)},
        {"nFcFirstChunk", "num", num_value(1)},
        {"nFcHbTimeout", "num", num_value(1)},
        {"bFcRun", "bool", bool_value(false)},
        {"nFcState", "num", num_value(0)},
        {"nFcChunkNow", "num", num_value(0)},
        {"nFcChunkDone", "num", num_value(0)},
        {"nFcBarrier", "num", num_value(0)},
        {"sFcMessage", "string", string_value("")},
    };
    std::size_t pers = 0;
    for (const DataDecl& d : fc_main().data) pers += d.storage == Storage::pers ? 1 : 0;
    EXPECT_EQ(pers, expected.size());
    for (const Expected& e : expected) {
        const DataDecl* d = fc_main().find_data(e.name);
        ASSERT_NE(d, nullptr) << e.name;
        EXPECT_EQ(d->name, e.name);  // RWS addresses PERS data by its exact name
        EXPECT_EQ(d->storage, Storage::pers) << e.name;
        EXPECT_EQ(d->visibility, Visibility::global) << e.name;
        EXPECT_EQ(d->type, e.type) << e.name;
        EXPECT_TRUE(d->dims.empty()) << e.name;
        ASSERT_TRUE(d->value.has_value()) << e.name;
        EXPECT_TRUE(*d->value == e.initial) << e.name << " = " << to_rapid_text(*d->value);
    }
    // The state codes of docs/irc5-setup.md.
    const std::map<std::string, double> states = {
        {"FC_IDLE", 0}, {"FC_RUNNING", 1}, {"FC_PAUSED", 2},  {"FC_HELD", 3},
        {"FC_DONE", 4}, {"FC_ABORTED", 5}, {"FC_REJECTED", 6}};
    for (const auto& [name, code] : states) {
        const DataDecl* d = fc_main().find_data(name);
        ASSERT_NE(d, nullptr) << name;
        EXPECT_EQ(d->storage, Storage::constant) << name;
        ASSERT_TRUE(d->value && d->value->is_num()) << name;
        EXPECT_EQ(d->value->num(), code) << name;
    }
}

TEST(FcMainModule, MainInitialisesThenServesRunsForever) {
    const Routine& main = routine("main");
    ASSERT_EQ(main.body.size(), 2u);
    const ProcCall* init = as_call(&main.body[0], "FcInit");
    ASSERT_NE(init, nullptr) << "main must start with FcInit";
    const auto* loop = std::get_if<While>(&main.body[1].node);
    ASSERT_NE(loop, nullptr);
    const auto* forever = std::get_if<Literal>(&loop->condition.node);
    ASSERT_NE(forever, nullptr);
    EXPECT_EQ(std::get<bool>(forever->value), true);

    // The run request is taken (cleared) before a run starts, and a stale one is cleared after
    // a program reset.
    const std::vector<const Statement*> wait_run = statements_of(routine("FcWaitRun"));
    const auto clears_run = [](const Statement* s) {
        const auto* a = std::get_if<Assign>(&s->node);
        return a != nullptr && name_of(&a->target) == "bFcRun" &&
               std::get_if<Literal>(&a->value.node) != nullptr &&
               std::get<bool>(std::get<Literal>(a->value.node).value) == false;
    };
    EXPECT_TRUE(std::any_of(wait_run.begin(), wait_run.end(), clears_run));
    const std::vector<const Statement*> init_seq = statements_of(routine("FcInit"));
    EXPECT_TRUE(std::any_of(init_seq.begin(), init_seq.end(), clears_run));
}

TEST(FcMainModule, ConnectsAndArmsEveryInterrupt) {
    // In FcInit each interrupt is deleted, connected, then ordered: IDelete x; CONNECT x WITH
    // trap; ISignalDI sig, value, x (or ITimer period, x). ExitCycle keeps interrupts, so the
    // IDelete must come first.
    const std::vector<const Statement*> seq = statements_of(routine("FcInit"));
    struct Armed {
        std::string trap, source;
        double value = 0;
        bool operator<(const Armed& o) const {
            return std::tie(trap, source, value) < std::tie(o.trap, o.source, o.value);
        }
        bool operator==(const Armed& o) const {
            return std::tie(trap, source, value) == std::tie(o.trap, o.source, o.value);
        }
    };
    std::set<Armed> armed;
    std::set<std::string> connected_traps;
    for (std::size_t i = 0; i < seq.size(); ++i) {
        const auto* c = std::get_if<Connect>(&seq[i]->node);
        if (c == nullptr) continue;
        const std::string intno = name_of(&c->interrupt);
        ASSERT_FALSE(intno.empty()) << "line " << seq[i]->line;
        const DataDecl* d = fc_main().find_data(intno);
        ASSERT_NE(d, nullptr) << intno;
        EXPECT_EQ(d->type, "intnum");
        EXPECT_EQ(d->storage, Storage::var);

        ASSERT_GT(i, 0u);
        const ProcCall* del = as_call(seq[i - 1], "IDelete");
        ASSERT_NE(del, nullptr) << "no IDelete " << intno << " before CONNECT";
        EXPECT_EQ(name_of(arg(*del, 0)), intno);

        ASSERT_LT(i + 1, seq.size());
        const ProcCall* order = as_call(seq[i + 1]);
        ASSERT_NE(order, nullptr) << "nothing orders " << intno;
        const Routine* trap = fc_main().find_routine(c->trap);
        ASSERT_NE(trap, nullptr);
        EXPECT_EQ(trap->kind, RoutineKind::trap);
        connected_traps.insert(trap->name);
        if (same_name(order->name, "ISignalDI")) {
            EXPECT_EQ(name_of(arg(*order, 2)), intno);
            const std::optional<double> v = num_of(arg(*order, 1));
            ASSERT_TRUE(v.has_value());
            armed.insert({trap->name, name_of(arg(*order, 0)), *v});
        } else if (same_name(order->name, "ITimer")) {
            EXPECT_EQ(name_of(arg(*order, 1)), intno);
            EXPECT_TRUE(order->args.size() == 2) << "the heartbeat timer must be cyclic";
            const DataDecl* period = fc_main().find_data(name_of(arg(*order, 0)));
            ASSERT_NE(period, nullptr);
            ASSERT_TRUE(period->value && period->value->is_num());
            EXPECT_GE(period->value->num(), 0.1);  // the shortest cyclic ITimer period
            EXPECT_LE(period->value->num(), 0.25);
            armed.insert({trap->name, "timer", period->value->num()});
        } else {
            ADD_FAILURE() << intno << " ordered by " << order->name;
        }
    }
    const std::set<Armed> expected = {
        {"FcOnAbort", "diFcAbort", 1},      {"FcOnPause", "diFcPause", 1},
        {"FcOnResume", "diFcPause", 0},     {"FcOnHbEdge", "diFcHeartbeat", 1},
        {"FcOnHbEdge", "diFcHeartbeat", 0}, {"FcOnTick", "timer", 0.1}};
    std::string found;
    for (const Armed& a : armed)
        found += "  " + a.trap + " <- " + a.source + " " + format_num(a.value) + "\n";
    EXPECT_TRUE(armed == expected) << found;

    // Every TRAP of the module is connected.
    std::set<std::string> traps;
    for (const Routine& r : fc_main().routines)
        if (r.kind == RoutineKind::trap) traps.insert(r.name);
    EXPECT_EQ(traps, connected_traps);
    EXPECT_EQ(traps, (std::set<std::string>{"FcOnAbort", "FcOnPause", "FcOnResume", "FcOnHbEdge",
                                            "FcOnTick"}));
}

TEST(FcMainModule, HeartbeatWatchdogStopsMotionAndDropsRunning) {
    const std::vector<const Statement*> tick = expanded(routine("FcOnTick"));
    // The robot's own heartbeat is toggled on every tick.
    const std::size_t toggle = find_call(tick, "SetDO");
    ASSERT_LT(toggle, tick.size());
    EXPECT_EQ(name_of(arg(*as_call(tick[toggle]), 0)), "doFcHeartbeat");
    // On a timeout during a run: doFcRunning low and StopMove.
    bool running_low = false;
    for (const Statement* s : tick)
        if (const ProcCall* c = as_call(s, "SetDO"))
            running_low = running_low || (name_of(arg(*c, 0)) == "doFcRunning" &&
                                          num_of(arg(*c, 1)) == std::optional<double>(0));
    EXPECT_TRUE(running_low);
    EXPECT_GE(count_calls(tick, "StopMove"), 1u);
    // An edge of the service's heartbeat resets the age.
    const std::vector<const Statement*> edge = statements_of(routine("FcOnHbEdge"));
    EXPECT_TRUE(std::any_of(edge.begin(), edge.end(), [](const Statement* s) {
        const auto* a = std::get_if<Assign>(&s->node);
        return a != nullptr && name_of(&a->target) == "nFcHbAge" &&
               num_of(&a->value) == std::optional<double>(0);
    }));
    // The timeout is the PERS parameter, converted to ticks with a floor and a ceiling.
    const std::vector<const Statement*> ticks = statements_of(routine("FcHbTicks"));
    EXPECT_TRUE(std::any_of(ticks.begin(), ticks.end(), [](const Statement* s) {
        const auto* a = std::get_if<Assign>(&s->node);
        return a != nullptr && mentions(a->value, "nFcHbTimeout");
    }));
    // A held barrier is not released: FcBarrier's wait includes the held flag.
    const std::vector<const Statement*> barrier = statements_of(routine("FcBarrier"));
    const std::size_t wait = find_call(barrier, "WaitUntil");
    ASSERT_LT(wait, barrier.size());
    EXPECT_TRUE(mentions(*arg(*as_call(barrier[wait]), 0), "bFcHeld"));
}

TEST(FcMainModule, PauseStopsAndResumeRestartsMotion) {
    EXPECT_GE(count_calls(expanded(routine("FcOnPause")), "StopMove"), 1u);
    EXPECT_GE(count_calls(expanded(routine("FcOnResume")), "StartMove"), 1u);
    // No TRAP waits: a waiting TRAP would delay every other interrupt, the abort included.
    for (const Routine& r : fc_main().routines) {
        if (r.kind != RoutineKind::trap) continue;
        const std::vector<const Statement*> seq = expanded(r);
        for (std::string_view w : {"WaitDI", "WaitGI", "WaitUntil", "WaitTime", "WaitLoad"})
            EXPECT_EQ(count_calls(seq, w), 0u) << r.name << " calls " << w;
    }
}

TEST(FcMainModule, AbortStopsClearsThePathAndRestartsTheCycle) {
    const std::vector<const Statement*> seq = expanded(routine("FcOnAbort"));
    const std::size_t stop = find_call(seq, "StopMove");
    const std::size_t clear = find_call(seq, "ClearPath", stop);
    const std::size_t start = find_call(seq, "StartMove", clear);
    const std::size_t exit = find_call(seq, "ExitCycle", start);
    EXPECT_LT(stop, clear);
    EXPECT_LT(clear, start);
    EXPECT_LT(start, exit);
    ASSERT_LT(exit, seq.size());
    std::size_t running_low = seq.size();
    for (std::size_t i = 0; i < exit; ++i)
        if (const ProcCall* c = as_call(seq[i], "SetDO"))
            if (name_of(arg(*c, 0)) == "doFcRunning" &&
                num_of(arg(*c, 1)) == std::optional<double>(0))
                running_low = i;
    EXPECT_LT(running_low, exit);

    // After ExitCycle, main starts again with FcInit, which unloads what the run left before it
    // re-arms the interrupts.
    const std::vector<const Statement*> init = expanded(routine("FcInit"));
    const std::size_t unload = find_call(init, "UnLoad");
    std::size_t first_connect = init.size();
    for (std::size_t i = 0; i < init.size() && first_connect == init.size(); ++i)
        if (std::holds_alternative<Connect>(init[i]->node)) first_connect = i;
    EXPECT_LT(unload, first_connect);
}

TEST(FcMainModule, LoadsChunksStartLoadWaitLoadCallUnload) {
    const Routine& run = routine("FcRunJob");
    const std::vector<const Statement*> seq = statements_of(run);

    const std::size_t start = find_call(seq, "StartLoad");
    const std::size_t wait = find_call(seq, "WaitLoad", start);
    std::size_t late = seq.size();
    for (std::size_t i = wait; i < seq.size() && late == seq.size(); ++i)
        if (std::holds_alternative<LateCall>(seq[i]->node)) late = i;
    const std::size_t unload = find_call(seq, "UnLoad", late);
    ASSERT_LT(start, seq.size());
    EXPECT_LT(start, wait);
    EXPECT_LT(wait, late);
    EXPECT_LT(late, unload);
    ASSERT_LT(unload, seq.size());

    // Every StartLoad in the module is dynamic (UnLoad-able, dropped at PP to main) and uses the
    // one load session that WaitLoad waits for.
    std::string session;
    for (const Routine& r : fc_main().routines)
        for (const Statement* s : statements_of(r))
            if (const ProcCall* c = as_call(s, "StartLoad")) {
                const Argument* dyn = find_optional(c->args, "Dynamic");
                ASSERT_NE(dyn, nullptr) << "StartLoad without \\Dynamic on line " << s->line;
                EXPECT_TRUE(dyn->is_switch());
                if (session.empty()) session = name_of(arg(*c, 1));
                EXPECT_EQ(name_of(arg(*c, 1)), session);
            }
    ASSERT_FALSE(session.empty());
    EXPECT_EQ(fc_main().find_data(session)->type, "loadsession");
    EXPECT_EQ(name_of(arg(*as_call(seq[wait]), 0)), session);

    // Double buffering: one StartLoad before the loop, one inside it before the late call, so
    // the next chunk loads while the current one runs.
    std::size_t loop_index = seq.size();
    for (std::size_t i = 0; i < seq.size() && loop_index == seq.size(); ++i)
        if (std::holds_alternative<While>(seq[i]->node)) loop_index = i;
    ASSERT_LT(loop_index, seq.size());
    EXPECT_LT(start, loop_index);
    const std::size_t prefetch = find_call(seq, "StartLoad", wait);
    EXPECT_LT(prefetch, late);
    std::vector<const Statement*> in_loop;
    walk(std::get<While>(seq[loop_index]->node).body, in_loop);
    const auto inside = [&](std::size_t i) {
        return std::find(in_loop.begin(), in_loop.end(), seq[i]) != in_loop.end();
    };
    EXPECT_TRUE(inside(wait));
    EXPECT_TRUE(inside(prefetch));
    EXPECT_TRUE(inside(late));
    EXPECT_TRUE(inside(unload));

    // The late-bound routine is the module name of the linked chunk, built by FcChunkName.
    const std::string routine_var = name_of(&std::get<LateCall>(seq[late]->node).routine);
    ASSERT_FALSE(routine_var.empty());
    bool named = false;
    for (std::size_t i = wait; i < late; ++i)
        if (const auto* a = std::get_if<Assign>(&seq[i]->node))
            named =
                named || (name_of(&a->target) == routine_var && mentions(a->value, "FcChunkName"));
    EXPECT_TRUE(named);

    // Loads, links and unloads are not split by an abort: the abort interrupt sleeps around
    // each of them and its input is checked after.
    for (std::size_t i = 0; i < seq.size(); ++i) {
        const ProcCall* c = as_call(seq[i]);
        if (c == nullptr || !(same_name(c->name, "StartLoad") || same_name(c->name, "WaitLoad") ||
                              same_name(c->name, "UnLoad")))
            continue;
        std::size_t sleep = seq.size(), watch = seq.size();
        for (std::size_t j = i; j-- > 0;)
            if (as_call(seq[j], "ISleep") != nullptr || as_call(seq[j], "IWatch") != nullptr) {
                sleep = as_call(seq[j], "ISleep") != nullptr ? j : seq.size();
                break;
            }
        watch = find_call(seq, "IWatch", i);
        ASSERT_LT(sleep, seq.size()) << c->name << " on line " << seq[i]->line;
        ASSERT_LT(watch, seq.size()) << c->name << " on line " << seq[i]->line;
        EXPECT_EQ(name_of(arg(*as_call(seq[sleep]), 0)), "iFcAbort");
        EXPECT_EQ(name_of(arg(*as_call(seq[watch]), 0)), "iFcAbort");
        EXPECT_EQ(find_call(seq, "ISleep", i), find_call(seq, "ISleep", watch))
            << "ISleep again before IWatch after line " << seq[i]->line;
        EXPECT_LT(find_call(seq, "FcCheckAbort", watch), seq.size());
    }
}

TEST(FcMainModule, BarrierPublishesItsNumberThenWaitsForTheRelease) {
    const std::vector<const Statement*> seq = statements_of(routine("FcBarrier"));
    ASSERT_FALSE(seq.empty());
    const auto* code = std::get_if<Assign>(&seq[0]->node);
    ASSERT_NE(code, nullptr);
    const auto* mod = std::get_if<Binary>(&code->value.node);
    ASSERT_NE(mod, nullptr);
    EXPECT_EQ(mod->op, BinaryOp::mod);
    const DataDecl* modulus = fc_main().find_data(name_of(&*mod->rhs));
    ASSERT_NE(modulus, nullptr);
    EXPECT_EQ(modulus->value->num(), 65536.0);

    const std::string var = name_of(&code->target);
    std::set<std::string> published;
    const std::size_t wait = find_call(seq, "WaitUntil");
    ASSERT_LT(wait, seq.size());
    for (std::size_t i = 0; i < wait; ++i)
        if (const ProcCall* c = as_call(seq[i], "SetGO")) {
            EXPECT_EQ(name_of(arg(*c, 1)), var);
            published.insert(name_of(arg(*c, 0)));
        }
    EXPECT_EQ(published, (std::set<std::string>{"goFcEvent", "goFcBarrier"}));
    const ProcCall& w = *as_call(seq[wait]);
    EXPECT_TRUE(mentions(*arg(w, 0), "GInput"));
    EXPECT_TRUE(mentions(*arg(w, 0), "giFcRelease"));
    EXPECT_TRUE(mentions(*arg(w, 0), var));
    EXPECT_NE(find_optional(w.args, "InPos"), nullptr);
}

TEST(FcMainModule, ChunkNamesAndPathsFollowTheChunkContract) {
    FuncRunner run(fc_main());
    EXPECT_EQ(run.call("FcChunkName", {num_value(1)}).string(), "FcChunk0001");
    EXPECT_EQ(run.call("FcChunkName", {num_value(42)}).string(), "FcChunk0042");
    EXPECT_EQ(run.call("FcChunkName", {num_value(9999)}).string(), "FcChunk9999");

    run.set("sFcJobDir", string_value("HOME:/fibrecell/job-12"));
    EXPECT_EQ(run.call("FcChunkPath", {num_value(7)}).string(),
              "HOME:/fibrecell/job-12/FcChunk0007.mod");
    run.set("sFcJobDir", string_value("HOME:/fibrecell/job-12/"));
    EXPECT_EQ(run.call("FcChunkPath", {num_value(7)}).string(),
              "HOME:/fibrecell/job-12/FcChunk0007.mod");
    run.set("sFcJobDir", string_value("HOME:"));
    EXPECT_EQ(run.call("FcChunkPath", {num_value(123)}).string(), "HOME:FcChunk0123.mod");

    // The longest accepted job folder still gives a path within RAPID's 80 characters.
    run.set("sFcJobDir", string_value(std::string(60, 'x')));
    EXPECT_LE(run.call("FcChunkPath", {num_value(9999)}).string().size(), 80u);

    // The heartbeat timeout in ticks, clamped.
    run.set("nFcHbTimeout", num_value(1));
    EXPECT_EQ(run.call("FcHbTicks", {}).num(), 10.0);
    run.set("nFcHbTimeout", num_value(0.05));
    EXPECT_EQ(run.call("FcHbTicks", {}).num(), 3.0);
    run.set("nFcHbTimeout", num_value(60));
    EXPECT_EQ(run.call("FcHbTicks", {}).num(), 100.0);
}

TEST(FcMainModule, ChunksLinkAgainstItsGlobalRoutinesOnly) {
    // The chunk writer's modules call FcBarrier; the reader accepts that when FcMain's global
    // routines are the external routines, and refuses FcMain's LOCAL ones.
    ValidateOptions o;
    o.known_signals = fc_signals;
    o.loaded_modules = {"FcMain"};
    for (const Routine& r : fc_main().routines)
        if (!r.local && r.kind == RoutineKind::proc)
            o.external_routines.push_back("FcMain:" + r.name);
    o.file_name = "FcChunk0007.mod";

    const CheckResult good = check_module(chunk_text("FcChunk0007", "FcBarrier 12;"), o);
    EXPECT_TRUE(good.ok() && good.diagnostics.empty()) << all(good.diagnostics);

    const CheckResult local = check_module(chunk_text("FcChunk0007", "FcAbort;"), o);
    EXPECT_FALSE(local.ok());
}
