// The RAPID reader on a generator-style chunk and a resident-main-style module: the model holds
// the declarations, statements and values a simulated controller needs to run them.

#include <gtest/gtest.h>

#include <string>

#include "drivers/abb/rapid/reader.hpp"
#include "tests/support/project_paths.hpp"

using namespace fibrecell::drivers::abb::rapid;

namespace {

const std::string data_dir = fibrecell::test::test_data_path("rapid/");

ValidateOptions chunk_options() {
    ValidateOptions o;
    o.known_signals = {"goEvent", "diExtruderReady"};
    return o;
}

ValidateOptions main_module_options() {
    ValidateOptions o;
    o.known_signals = {"goEvent", "diJobReady", "diAbort"};
    return o;
}

std::string diagnostics_text(const std::vector<Diagnostic>& ds) {
    std::string out;
    for (const Diagnostic& d : ds) out += format(d) + "\n";
    return out;
}

template <class T>
const T& as(const Statement& s) {
    const T* p = std::get_if<T>(&s.node);
    if (p == nullptr)
        throw std::runtime_error("statement on line " + std::to_string(s.line) +
                                 " has another kind");
    return *p;
}

double num_literal(const Expr& e) {
    if (const auto* u = std::get_if<Unary>(&e.node)) return -num_literal(*u->operand);
    return std::get<double>(std::get<Literal>(e.node).value);
}

}  // namespace

TEST(RapidReader, ChunkModuleParsesIntoTheModel) {
    const CheckResult r = check_module_file(data_dir + "Print_0001.mod", chunk_options());
    ASSERT_TRUE(r.ok()) << diagnostics_text(r.diagnostics);
    EXPECT_TRUE(r.diagnostics.empty()) << diagnostics_text(r.diagnostics);
    const Module& m = *r.module;
    EXPECT_EQ(m.name, "Print_0001");
    EXPECT_EQ(m.file, "Print_0001.mod");
    EXPECT_EQ(m.header, (std::vector<std::string>{"VERSION:1", "LANGUAGE:ENGLISH"}));
    EXPECT_EQ(m.line, 5u);
    EXPECT_EQ(m.line_count, 31u);

    ASSERT_EQ(m.data.size(), 8u);
    const DataDecl* tpla = m.find_data("tpla");  // case-insensitive
    ASSERT_NE(tpla, nullptr);
    EXPECT_EQ(tpla->storage, Storage::pers);
    EXPECT_EQ(tpla->type, "tooldata");
    EXPECT_EQ(tpla->line, 8u);
    ASSERT_TRUE(tpla->value);
    const auto tool = to_tooldata(*tpla->value);
    ASSERT_TRUE(tool);
    EXPECT_TRUE(tool->robhold);
    EXPECT_DOUBLE_EQ(tool->tframe.trans_mm.y(), -72.5);
    EXPECT_DOUBLE_EQ(tool->tframe.trans_mm.z(), 118.3);
    EXPECT_DOUBLE_EQ(tool->tframe.rot.w(), 0.965926);
    EXPECT_DOUBLE_EQ(tool->tframe.rot.y(), 0.258819);
    EXPECT_DOUBLE_EQ(tool->tload.mass_kg, 0.85);
    EXPECT_DOUBLE_EQ(tool->tload.cog_mm.z(), 60.0);

    const auto bed = to_wobjdata(*m.find_data("wBed")->value);
    ASSERT_TRUE(bed);
    EXPECT_FALSE(bed->robhold);
    EXPECT_DOUBLE_EQ(bed->uframe.trans_mm.x(), 400.0);
    const auto print_speed = to_speeddata(*m.find_data("vPrint")->value);
    ASSERT_TRUE(print_speed);
    EXPECT_DOUBLE_EQ(print_speed->v_tcp_mm_s, 30.0);
    EXPECT_DOUBLE_EQ(print_speed->v_leax_mm_s, 5000.0);
    EXPECT_EQ(m.find_data("tgPathStart")->type, "triggdata");
    EXPECT_EQ(m.find_data("pSafe")->storage, Storage::constant);

    ASSERT_EQ(m.routines.size(), 1u);
    const Routine& proc = m.routines[0];
    EXPECT_EQ(proc.kind, RoutineKind::proc);
    EXPECT_EQ(proc.name, "Print_0001");
    EXPECT_EQ(proc.end_line, 30u);
    ASSERT_EQ(proc.body.size(), 11u);

    const auto& confj = as<ProcCall>(proc.body[0]);
    EXPECT_EQ(confj.name, "ConfJ");
    ASSERT_EQ(confj.args.size(), 1u);
    EXPECT_TRUE(confj.args[0].is_switch());
    EXPECT_EQ(confj.args[0].name, "On");

    // TriggIO tgPathStart, 0 \Start \GOp:=goEvent, 17;
    const auto& trigg_io = as<ProcCall>(proc.body[2]);
    EXPECT_EQ(proc.body[2].line, 21u);
    EXPECT_EQ(trigg_io.name, "TriggIO");
    const auto positional = positional_args(trigg_io.args);
    ASSERT_EQ(positional.size(), 3u);
    EXPECT_EQ(std::get<NameRef>(positional[0]->node).name, "tgPathStart");
    EXPECT_EQ(num_literal(*positional[1]), 0.0);
    EXPECT_EQ(num_literal(*positional[2]), 17.0);
    ASSERT_NE(find_optional(trigg_io.args, "Start"), nullptr);
    EXPECT_TRUE(find_optional(trigg_io.args, "Start")->is_switch());
    const Argument* gop = find_optional(trigg_io.args, "GOp");
    ASSERT_NE(gop, nullptr);
    ASSERT_TRUE(gop->value);
    EXPECT_EQ(std::get<NameRef>(gop->value->node).name, "goEvent");

    // MoveL <inline robtarget>, vTravel, fine, tPLA \WObj:=wBed;
    const auto& movel = as<ProcCall>(proc.body[5]);
    EXPECT_EQ(movel.name, "MoveL");
    ASSERT_EQ(positional_args(movel.args).size(), 4u);
    const Argument* wobj = find_optional(movel.args, "WObj");
    ASSERT_NE(wobj, nullptr);
    EXPECT_EQ(std::get<NameRef>(wobj->value->node).name, "wBed");
    const auto target = to_robtarget(evaluate(*positional_args(movel.args)[0], {}));
    ASSERT_TRUE(target);
    EXPECT_DOUBLE_EQ(target->trans_mm.x(), 10.0);
    EXPECT_DOUBLE_EQ(target->trans_mm.z(), 0.8);
    EXPECT_DOUBLE_EQ(target->rot.w(), 0.0);
    EXPECT_DOUBLE_EQ(target->rot.y(), 1.0);  // [q1,q2,q3,q4] = (w,x,y,z)
    EXPECT_EQ(target->conf.cf1, 0);
    EXPECT_EQ(target->conf.cf6, -1);
    EXPECT_EQ(target->conf.cfx, 1);
    EXPECT_EQ(target->extax[0], 9e9);

    // The comma form ",\WObj:=" parses like the space form.
    const auto& last_trigg = as<ProcCall>(proc.body[9]);
    EXPECT_EQ(last_trigg.name, "TriggL");
    EXPECT_NE(find_optional(last_trigg.args, "WObj"), nullptr);
    EXPECT_EQ(positional_args(last_trigg.args).size(), 5u);
}

TEST(RapidReader, MoveTargetsListEveryTargetWithToolAndWobj) {
    const Module m = read_module_file(data_dir + "Print_0001.mod", chunk_options());
    const std::vector<MoveTarget> targets = move_targets(m);
    ASSERT_EQ(targets.size(), 6u);
    EXPECT_EQ(targets[0].instruction, "MoveJ");
    EXPECT_EQ(targets[0].target_name, "pSafe");
    EXPECT_EQ(targets[0].declared_line, 15u);
    EXPECT_EQ(targets[0].line, 23u);
    ASSERT_TRUE(targets[0].robtarget);
    EXPECT_DOUBLE_EQ(targets[0].robtarget->trans_mm.z(), 80.0);
    for (const MoveTarget& t : targets) {
        EXPECT_EQ(t.tool, "tPLA");
        EXPECT_EQ(t.wobj, "wBed");
        ASSERT_TRUE(t.tool_data);
        ASSERT_TRUE(t.wobj_data);
        EXPECT_DOUBLE_EQ(t.wobj_data->uframe.trans_mm.y(), -150.0);
        ASSERT_TRUE(t.robtarget) << "line " << t.line;
    }
    EXPECT_EQ(targets[2].instruction, "TriggL");
    EXPECT_EQ(targets[2].line, 26u);
    EXPECT_TRUE(targets[2].target_name.empty());
    EXPECT_DOUBLE_EQ(targets[2].robtarget->trans_mm.x(), 30.0);
    // Offs(pSafe, 0, 0, 20) evaluated from the CONST.
    EXPECT_DOUBLE_EQ(targets[5].robtarget->trans_mm.z(), 100.0);
}

TEST(RapidReader, ResidentMainParses) {
    const CheckResult r = check_module_file(data_dir + "FcMain.mod", main_module_options());
    ASSERT_TRUE(r.ok()) << diagnostics_text(r.diagnostics);
    EXPECT_TRUE(r.diagnostics.empty()) << diagnostics_text(r.diagnostics);
    const Module& m = *r.module;
    ASSERT_EQ(m.routines.size(), 4u);
    EXPECT_EQ(m.find_routine("ChunkName")->kind, RoutineKind::func);
    EXPECT_EQ(m.find_routine("ChunkName")->return_type, "string");
    ASSERT_EQ(m.find_routine("ChunkName")->params.size(), 1u);
    EXPECT_EQ(m.find_routine("tAbort")->kind, RoutineKind::trap);
    EXPECT_EQ(m.find_data("lsNext")->type, "loadsession");
    EXPECT_EQ(std::get<double>(m.find_data("EV_JOB_END")->value->data), 2.0);

    const Routine& main = *m.find_routine("main");
    ASSERT_EQ(main.body.size(), 5u);
    const auto& connect = as<Connect>(main.body[2]);
    EXPECT_EQ(connect.trap, "tAbort");
    const auto& loop = as<While>(main.body[4]);
    EXPECT_EQ(std::get<Literal>(loop.condition.node).value,
              (std::variant<double, bool, std::string>(true)));
    ASSERT_EQ(loop.body.size(), 9u);

    // IF nChunks > 0 StartLoad ...;  (the one-statement IF)
    const auto& compact_if = as<If>(loop.body[3]);
    ASSERT_EQ(compact_if.branches.size(), 1u);
    const auto& start_load = as<ProcCall>(compact_if.branches[0].body.at(0));
    EXPECT_EQ(start_load.name, "StartLoad");
    EXPECT_TRUE(find_optional(start_load.args, "Dynamic")->is_switch());
    EXPECT_EQ(positional_args(start_load.args).size(), 2u);

    const auto& chunks = as<While>(loop.body[4]);
    ASSERT_EQ(chunks.body.size(), 6u);
    EXPECT_EQ(as<ProcCall>(chunks.body[0]).name, "WaitLoad");
    const auto& branches = as<If>(chunks.body[2]);
    EXPECT_EQ(branches.branches.size(), 2u);
    EXPECT_EQ(branches.else_body.size(), 1u);
    const auto& late = as<LateCall>(chunks.body[3]);
    EXPECT_TRUE(std::holds_alternative<Binary>(late.routine.node));
    EXPECT_EQ(as<ProcCall>(chunks.body[5]).name, "Incr");

    const auto& test = as<TestStatement>(loop.body[5]);
    ASSERT_EQ(test.cases.size(), 2u);
    EXPECT_EQ(test.cases[1].values.size(), 3u);
    EXPECT_TRUE(test.has_default);
    const auto& literal_late = as<LateCall>(loop.body[6]);
    EXPECT_EQ(std::get<std::string>(std::get<Literal>(literal_late.routine.node).value),
              "FcMain:GoSafe");
}

TEST(RapidReader, EvaluatesExpressionsWithASimulatorsData) {
    const Module m = read_module_file(data_dir + "FcMain.mod", main_module_options());
    const Routine& f = *m.find_routine("ChunkName");
    // The FUNC's body, run by hand the way a simulator would.
    Value s = string_value("");
    Value n = num_value(7);
    const EvalContext context{[&](std::string_view name) -> const Value* {
                                  if (same_name(name, "s")) return &s;
                                  if (same_name(name, "n")) return &n;
                                  return nullptr;
                              },
                              {}};
    s = evaluate(as<Assign>(f.body[0]).value, context);
    const auto& loop = as<While>(f.body[1]);
    while (evaluate(loop.condition, context).boolean())
        s = evaluate(as<Assign>(loop.body[0]).value, context);
    EXPECT_EQ(evaluate(*as<Return>(f.body[2]).value, context).string(), "Print_0007");
}

TEST(RapidReader, PredefinedDataResolvesByName) {
    const auto v100 = to_speeddata(predefined_data("v100")->value);
    ASSERT_TRUE(v100);
    EXPECT_DOUBLE_EQ(v100->v_tcp_mm_s, 100.0);
    EXPECT_DOUBLE_EQ(v100->v_ori_deg_s, 500.0);
    EXPECT_DOUBLE_EQ(to_speeddata(predefined_data("V7000")->value)->v_tcp_mm_s, 7000.0);
    EXPECT_TRUE(predefined_data("vmax"));
    EXPECT_FALSE(predefined_data("v7"));
    const auto fine = to_zonedata(predefined_data("fine")->value);
    EXPECT_TRUE(fine->finep);
    const auto z10 = to_zonedata(predefined_data("z10")->value);
    EXPECT_FALSE(z10->finep);
    EXPECT_DOUBLE_EQ(z10->pzone_ori_mm, 15.0);
    EXPECT_DOUBLE_EQ(to_zonedata(predefined_data("z0")->value)->pzone_tcp_mm, 0.3);
    EXPECT_DOUBLE_EQ(to_zonedata(predefined_data("z200")->value)->pzone_tcp_mm, 200.0);
    const auto tool0 = to_tooldata(predefined_data("tool0")->value);
    EXPECT_TRUE(tool0->tframe.trans_mm.isZero());
    EXPECT_FALSE(predefined_data("tool0")->constant);
    EXPECT_TRUE(to_wobjdata(predefined_data("wobj0")->value));
    EXPECT_TRUE(to_loaddata(predefined_data("load0")->value));
}

TEST(RapidReader, EvaluatorFollowsRapidSemantics) {
    auto eval = [](std::string_view expr) {
        const std::string text =
            "MODULE M\n  CONST num x := " + std::string(expr) + ";\nENDMODULE\n";
        const ParseResult r = parse_module(text);
        if (!r.module) throw std::runtime_error("no parse: " + std::string(expr));
        return evaluate(*r.module->data[0].init, {});
    };
    EXPECT_DOUBLE_EQ(eval("7 DIV 2").num(), 3.0);
    EXPECT_DOUBLE_EQ(eval("7 MOD 3").num(), 1.0);
    EXPECT_DOUBLE_EQ(eval("-2 * 3 + 10 / 4").num(), -3.5);
    EXPECT_DOUBLE_EQ(eval("Sin(30)").num(), 0.5);  // degrees
    EXPECT_DOUBLE_EQ(eval("Round(2.3456 \\Dec:=2)").num(), 2.35);
    EXPECT_TRUE(eval("NOT 1 > 2 AND 2 >= 2").boolean());
    EXPECT_TRUE(eval("TRUE XOR FALSE").boolean());
    EXPECT_EQ(eval("NumToStr(3.14159, 2)").string(), "3.14");
    EXPECT_EQ(eval("\"a\"\"b\" + \"c\"").string(), "a\"bc");
    EXPECT_DOUBLE_EQ(eval("[1,2,3]").items()[2].num(), 3.0);
    EXPECT_DOUBLE_EQ(eval("9E+09").num(), 9e9);
    EXPECT_DOUBLE_EQ(eval("0x1F").num(), 31.0);
    EXPECT_THROW(eval("1 / 0"), EvalError);
    EXPECT_THROW(eval("7.5 DIV 2"), EvalError);
    EXPECT_THROW(eval("1 + \"a\""), EvalError);
    EXPECT_THROW(eval("Unknown(1)"), EvalError);

    // Component access on typed records, index access on arrays.
    const Module m = read_module(
        "MODULE M\n"
        "  CONST robtarget p := [[1,2,3],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n"
        "  CONST num a{2,3} := [[1,2,3],[4,5,6]];\n"
        "  CONST num z := p.trans.z + a{2,3};\n"
        "ENDMODULE\n");
    EXPECT_DOUBLE_EQ(std::get<double>(m.data[2].value->data), 9.0);
    EXPECT_EQ(m.data[1].extents, (std::vector<std::size_t>{2, 3}));
    EXPECT_EQ(component(*m.data[0].value, "robconf")->items().size(), 4u);
}

TEST(RapidReader, DefaultsAndTypedConversionsRoundTrip) {
    const auto d = default_value("robtarget");
    ASSERT_TRUE(d);
    EXPECT_EQ(d->type, "robtarget");
    EXPECT_TRUE(to_robtarget(*d));
    Robtarget t;
    t.trans_mm = {1, 2, 3};
    t.rot = Eigen::Quaterniond(0.5, 0.5, -0.5, 0.5);
    t.conf = {-1, 0, 2, 5};
    const auto back = to_robtarget(to_value(t));
    ASSERT_TRUE(back);
    EXPECT_EQ(back->trans_mm, t.trans_mm);
    EXPECT_EQ(back->rot.coeffs(), t.rot.coeffs());
    EXPECT_EQ(back->conf.cf6, 2);
    EXPECT_EQ(back->conf.cfx, 5);
    EXPECT_EQ(to_rapid_text(to_value(SpeedData{30, 500, 5000, 1000})), "[30,500,5000,1000]");
    EXPECT_FALSE(to_robtarget(items_value({num_value(1)})));
    const auto arr = default_value("num", {2, 2});
    EXPECT_EQ(arr->items().size(), 2u);
    EXPECT_EQ(arr->items()[1].items().size(), 2u);
}
