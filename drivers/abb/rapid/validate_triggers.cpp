// Position events: every triggdata a TriggL/TriggJ fires must have been set up by TriggIO,
// TriggEquip, TriggInt or TriggSpeed earlier in the same routine (docs/rapid-subset.md, "Position
// events"). "Earlier" is source order, which is execution order for the straight-line chunks the
// generator emits.

#include <set>

#include "drivers/abb/rapid/instructions.hpp"
#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/validate_detail.hpp"

namespace fibrecell::drivers::abb::rapid::detail {
namespace {

class TriggerWalk {
  public:
    TriggerWalk(Checker& c, const Routine& r) : c_(c), r_(r) {}

    void block(const Block& b) {
        for (const Statement& s : b) statement(s);
    }

  private:
    void statement(const Statement& s) {
        if (const auto* call = std::get_if<ProcCall>(&s.node)) return this->call(*call);
        if (const auto* i = std::get_if<If>(&s.node)) {
            for (const IfBranch& b : i->branches) block(b.body);
            block(i->else_body);
        } else if (const auto* w = std::get_if<While>(&s.node)) {
            block(w->body);
        } else if (const auto* f = std::get_if<For>(&s.node)) {
            block(f->body);
        } else if (const auto* t = std::get_if<TestStatement>(&s.node)) {
            for (const TestCase& c : t->cases) block(c.body);
            block(t->default_body);
        }
    }

    void call(const ProcCall& call) {
        const InstructionInfo* info = find_instruction(call.name);
        if (info == nullptr) return;
        if (info->sets_up_trigger) {
            if (const Expr* e = positional(call.args, 0))
                if (const auto* n = std::get_if<NameRef>(&e->node)) ready_.insert(fold(n->name));
            return;
        }
        if (info->move.trigger < 0) return;
        std::vector<const Expr*> triggers;
        if (const Expr* e = positional(call.args, static_cast<std::size_t>(info->move.trigger)))
            triggers.push_back(e);
        for (const Argument& a : call.args)
            if (!a.positional() && is_extra_trigger(a.name) && a.value)
                triggers.push_back(&*a.value);
        for (const Expr* e : triggers) {
            const auto* n = std::get_if<NameRef>(&e->node);
            if (n == nullptr) {
                c_.report(Rule::trigger_setup, e->line,
                          std::string(info->name) + " trigger arguments must name triggdata");
                continue;
            }
            const auto s = c_.find_symbol(n->name);
            if (!s || !same_name(s->type, "triggdata")) continue;  // reported as name/type errors
            if (ready_.count(fold(n->name)) == 0)
                c_.report(Rule::trigger_setup, e->line,
                          "trigger '" + n->name + "' of " + std::string(info->name) +
                              " is not set up by TriggIO, TriggEquip, TriggInt or TriggSpeed "
                              "earlier in " +
                              r_.name);
        }
    }

    Checker& c_;
    const Routine& r_;
    std::set<std::string> ready_;
};

}  // namespace

void Checker::check_triggers(const Routine& r) {
    TriggerWalk(*this, r).block(r.body);
}

}  // namespace fibrecell::drivers::abb::rapid::detail
