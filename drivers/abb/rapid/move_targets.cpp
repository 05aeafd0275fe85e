#include "drivers/abb/rapid/move_targets.hpp"

#include <map>

#include "drivers/abb/rapid/evaluate.hpp"
#include "drivers/abb/rapid/instructions.hpp"
#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/predefined.hpp"

namespace fibrecell::drivers::abb::rapid {
namespace {

class Collector {
  public:
    Collector(const Module& m, std::vector<MoveTarget>& out) : m_(m), out_(out) {}

    void routine(const Routine& r) {
        r_ = &r;
        tools_.clear();
        wobjs_.clear();
        block(r.body);
    }

  private:
    const DataDecl* find_decl(std::string_view name) const {
        for (const DataDecl& d : r_->locals)
            if (same_name(d.name, name)) return &d;
        return m_.find_data(name);
    }

    const Value* lookup(std::string_view name) const {
        if (const DataDecl* d = find_decl(name)) return d->value ? &*d->value : nullptr;
        const PredefinedData* p = predefined_data(name);
        return p != nullptr ? &p->value : nullptr;
    }

    std::optional<Value> value_of(const Expr& e) {
        try {
            return evaluate(e, EvalContext{[this](std::string_view n) { return lookup(n); }, {}});
        } catch (const EvalError&) {
            return std::nullopt;
        }
    }

    // Tools and work objects repeat on every move: convert each name once per routine.
    template <class T>
    std::optional<T> resolve(std::map<std::string, std::optional<T>>& cache, const Expr& e,
                             std::optional<T> (*convert)(const Value&)) {
        const auto* n = std::get_if<NameRef>(&e.node);
        if (n != nullptr) {
            if (const auto it = cache.find(fold(n->name)); it != cache.end()) return it->second;
        }
        const auto v = value_of(e);
        std::optional<T> out = v ? convert(*v) : std::nullopt;
        if (n != nullptr) cache[fold(n->name)] = out;
        return out;
    }

    void block(const Block& b) {
        for (const Statement& s : b) {
            if (const auto* c = std::get_if<ProcCall>(&s.node))
                call(*c, s.line);
            else if (const auto* i = std::get_if<If>(&s.node)) {
                for (const IfBranch& br : i->branches) block(br.body);
                block(i->else_body);
            } else if (const auto* w = std::get_if<While>(&s.node))
                block(w->body);
            else if (const auto* f = std::get_if<For>(&s.node))
                block(f->body);
            else if (const auto* t = std::get_if<TestStatement>(&s.node)) {
                for (const TestCase& tc : t->cases) block(tc.body);
                block(t->default_body);
            }
        }
    }

    void call(const ProcCall& c, std::size_t line) {
        const InstructionInfo* info = find_instruction(c.name);
        if (info == nullptr || !is_motion(*info)) return;
        const auto args = positional_args(c.args);
        auto arg = [&](int i) -> const Expr* {
            return i >= 0 && static_cast<std::size_t>(i) < args.size()
                       ? args[static_cast<std::size_t>(i)]
                       : nullptr;
        };
        MoveTarget base;
        base.routine = r_->name;
        base.instruction = std::string(info->name);
        base.line = line;
        if (const Expr* tool = arg(info->move.tool)) {
            if (const auto* n = std::get_if<NameRef>(&tool->node)) base.tool = n->name;
            base.tool_data = resolve(tools_, *tool, to_tooldata);
        }
        static const Expr wobj0{NameRef{"wobj0"}, 0};
        const Argument* w = find_optional(c.args, "WObj");
        const Expr& wobj = w != nullptr && w->value ? *w->value : wobj0;
        const auto* wobj_name = std::get_if<NameRef>(&wobj.node);
        base.wobj = wobj_name != nullptr ? wobj_name->name : std::string();
        base.wobj_data = resolve(wobjs_, wobj, to_wobjdata);
        const bool joint = same_name(info->name, "MoveAbsJ");
        for (const auto& [index, circle] :
             {std::pair{info->move.via, true}, std::pair{info->move.target, false}}) {
            const Expr* e = arg(index);
            if (e == nullptr) continue;
            MoveTarget t = base;
            t.circle_point = circle;
            if (const auto* n = std::get_if<NameRef>(&e->node)) {
                t.target_name = n->name;
                if (const DataDecl* d = find_decl(n->name)) t.declared_line = d->line;
            }
            if (const auto v = value_of(*e)) {
                if (joint)
                    t.jointtarget = to_jointtarget(*v);
                else
                    t.robtarget = to_robtarget(*v);
            }
            out_.push_back(std::move(t));
        }
    }

    const Module& m_;
    std::vector<MoveTarget>& out_;
    const Routine* r_ = nullptr;
    std::map<std::string, std::optional<ToolData>> tools_;
    std::map<std::string, std::optional<WobjData>> wobjs_;
};

}  // namespace

std::vector<MoveTarget> move_targets(const Module& module) {
    std::vector<MoveTarget> out;
    Collector collector(module, out);
    for (const Routine& r : module.routines) collector.routine(r);
    return out;
}

}  // namespace fibrecell::drivers::abb::rapid
