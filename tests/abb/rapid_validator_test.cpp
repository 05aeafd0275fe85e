// One test per validator rule: a small bad module and the diagnostic (rule, line) it must give;
// the good module gives none.

#include <gtest/gtest.h>

#include <string>

#include "drivers/abb/rapid/reader.hpp"

using namespace fibrecell::drivers::abb::rapid;

namespace {

// Line 1 MODULE, 2-4 the standard data, then `extra` (k lines), then PROC at 5+k, body at 6+k.
std::string chunk(std::string_view extra, std::string_view body) {
    std::string text =
        "MODULE M\n"
        "  PERS tooldata tNozzle := [TRUE,[[0,0,100],[1,0,0,0]],[0.5,[0,0,50],[1,0,0,0],0,0,0]];\n"
        "  VAR speeddata vPrint := [30,500,5000,1000];\n"
        "  VAR triggdata tgOn;\n";
    text += extra;
    text += "  PROC M()\n";
    text += body;
    text += "  ENDPROC\nENDMODULE\n";
    return text;
}

constexpr std::string_view target =
    "[[10,20,0.8],[0.000000,0.000000,1.000000,0.000000],[0,0,-1,1],[9E9,9E9,9E9,9E9,9E9,9E9]]";

std::string good_body() {
    return "    TriggIO tgOn, 0 \\Start \\GOp:=goEvent, 17;\n"
           "    MoveL " +
           std::string(target) +
           ", vPrint, fine, tNozzle \\WObj:=wobj0;\n"
           "    TriggL " +
           std::string(target) + ", vPrint, tgOn, z0, tNozzle \\WObj:=wobj0;\n";
}

ValidateOptions validator_options() {
    ValidateOptions o;
    o.known_signals = {"goEvent", "diReady"};
    return o;
}

std::vector<Diagnostic> diagnose(std::string_view text, const ValidateOptions& o = validator_options()) {
    return check_module(text, o).diagnostics;
}

std::string indented_diagnostics(const std::vector<Diagnostic>& ds) {
    std::string out;
    for (const Diagnostic& d : ds) out += "  " + format(d) + "\n";
    return out;
}

// The diagnostics include one with `rule` on `line`.
::testing::AssertionResult reports(const std::vector<Diagnostic>& ds, Rule rule, std::size_t line) {
    for (const Diagnostic& d : ds)
        if (d.rule == rule && d.line == line) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "no [" << to_string(rule) << "] on line " << line << "; got:\n"
           << indented_diagnostics(ds);
}

}  // namespace

TEST(RapidValidator, GoodModuleHasNoDiagnostics) {
    const CheckResult r = check_module(chunk("", good_body()), validator_options());
    EXPECT_TRUE(r.ok());
    EXPECT_TRUE(r.diagnostics.empty()) << indented_diagnostics(r.diagnostics);
}

TEST(RapidValidator, CrLfLineEndsAndLowerCaseKeywordsAreFine) {
    std::string text = chunk("", good_body());
    std::string crlf;
    for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    EXPECT_TRUE(diagnose(crlf).empty()) << indented_diagnostics(diagnose(crlf));
    EXPECT_TRUE(diagnose("module m\n  proc m()\n    stop;\n  endproc\nendmodule\n").empty());
}

TEST(RapidValidator, Encoding) {
    EXPECT_TRUE(reports(diagnose(chunk("  ! caf\xC3\xA9\n", good_body())), Rule::encoding, 5));
    EXPECT_TRUE(reports(diagnose("\xEF\xBB\xBF" + chunk("", good_body())), Rule::encoding, 1));
    EXPECT_TRUE(reports(diagnose(chunk("  ! bell \a\n", good_body())), Rule::encoding, 5));
}

TEST(RapidValidator, LineEnding) {
    EXPECT_TRUE(reports(diagnose("MODULE M\r\r\n" + chunk("", good_body()).substr(9)),
                        Rule::line_ending, 1));
    EXPECT_TRUE(
        reports(diagnose(chunk("  ! old mac\r  VAR num n;\n", good_body())), Rule::line_ending, 5));
}

TEST(RapidValidator, LineCount) {
    ValidateOptions o = validator_options();
    o.max_lines = 5;
    EXPECT_TRUE(reports(diagnose(chunk("", good_body()), o), Rule::line_count, 6));
    o.max_lines = 11;
    EXPECT_TRUE(diagnose(chunk("", good_body()), o).empty());
}

TEST(RapidValidator, Syntax) {
    EXPECT_TRUE(
        reports(diagnose(chunk("", "    MoveL p10 v100, fine, tool0;\n")), Rule::syntax, 6));
    EXPECT_TRUE(reports(diagnose(chunk("", "    WaitTime 1\n    Stop;\n")), Rule::syntax, 7));
    EXPECT_TRUE(reports(diagnose(chunk("", "    GOTO lbl;\n")), Rule::syntax, 6));
    EXPECT_TRUE(reports(diagnose(chunk("  VAR num n := 1.5.3;\n", "")), Rule::syntax, 5));
    EXPECT_TRUE(reports(diagnose(chunk("  VAR string s := \"open;\n", "")), Rule::syntax, 5));
    EXPECT_TRUE(reports(diagnose(chunk("  VAR num n := 12abc;\n", "")), Rule::syntax, 5));
    EXPECT_TRUE(reports(diagnose(chunk("", "    RETURN 1;\n")), Rule::syntax, 6));
}

TEST(RapidValidator, BlockBalance) {
    // IF closed by ENDWHILE.
    const auto wrong_end = diagnose(chunk("", "    IF TRUE THEN\n      Stop;\n    ENDWHILE\n"));
    EXPECT_TRUE(reports(wrong_end, Rule::block, 8));
    // PROC never closed before ENDMODULE.
    EXPECT_TRUE(reports(diagnose("MODULE M\n  PROC M()\n    Stop;\nENDMODULE\n"), Rule::block, 4));
    // MODULE never closed.
    EXPECT_TRUE(reports(diagnose("MODULE M\n  PROC M()\n  ENDPROC\n"), Rule::block, 1));
    // WHILE without ENDWHILE, cut off by ENDPROC.
    EXPECT_TRUE(reports(diagnose(chunk("", "    WHILE TRUE DO\n      Stop;\n")), Rule::block, 8));
}

TEST(RapidValidator, NestingDepth) {
    const std::string deep = std::string(200, '(') + "1" + std::string(200, ')');
    EXPECT_TRUE(
        reports(diagnose(chunk("  VAR num n := " + deep + ";\n", "")), Rule::nesting_depth, 5));
    std::string body;
    for (int i = 0; i < 100; ++i) body += "IF TRUE THEN\n";
    EXPECT_FALSE(check_module(chunk("", body)).module);
}

TEST(RapidValidator, IdentifierLength) {
    const std::string name(33, 'a');
    EXPECT_TRUE(
        reports(diagnose(chunk("  VAR num " + name + ";\n", "")), Rule::identifier_length, 5));
    EXPECT_TRUE(diagnose(chunk("  VAR num " + std::string(32, 'a') + ";\n", "")).empty());
}

TEST(RapidValidator, StringLength) {
    const std::string s(81, 'x');
    EXPECT_TRUE(
        reports(diagnose(chunk("", "    TPWrite \"" + s + "\";\n")), Rule::string_length, 6));
    EXPECT_TRUE(diagnose(chunk("", "    TPWrite \"" + std::string(80, 'x') + "\";\n")).empty());
    // "" counts as one character.
    EXPECT_TRUE(diagnose(chunk("", "    TPWrite \"" + std::string(78, 'x') + "\"\"\";\n")).empty());
}

TEST(RapidValidator, ReservedWord) {
    EXPECT_TRUE(reports(diagnose(chunk("  VAR num While := 1;\n", "")), Rule::reserved_word, 5));
    EXPECT_TRUE(reports(diagnose(chunk("  PROC Step()\n  ENDPROC\n", "")), Rule::reserved_word, 5));
}

TEST(RapidValidator, BuiltinName) {
    EXPECT_TRUE(reports(diagnose(chunk("  VAR speeddata v100 := [100,500,5000,1000];\n", "")),
                        Rule::builtin_name, 5));
    EXPECT_TRUE(reports(diagnose(chunk("  PERS tooldata tool0 := [TRUE,[[0,0,0],[1,0,0,0]],"
                                       "[1,[0,0,1],[1,0,0,0],0,0,0]];\n",
                                       "")),
                        Rule::builtin_name, 5));
    EXPECT_TRUE(reports(diagnose(chunk("  VAR num fine;\n", "")), Rule::builtin_name, 5));
    EXPECT_TRUE(reports(diagnose(chunk("  PROC MoveL()\n  ENDPROC\n", "")), Rule::builtin_name, 5));
    EXPECT_TRUE(reports(diagnose(chunk("  VAR num robtarget;\n", "")), Rule::builtin_name, 5));
    EXPECT_TRUE(reports(diagnose(chunk("  VAR num Offs;\n", "")), Rule::builtin_name, 5));
    EXPECT_TRUE(reports(diagnose(chunk("", "    FOR z10 FROM 1 TO 2 DO\n    ENDFOR\n")),
                        Rule::builtin_name, 6));
}

TEST(RapidValidator, DuplicateName) {
    EXPECT_TRUE(reports(diagnose(chunk("  VAR num vPrint;\n", "")), Rule::duplicate_name, 5));
    EXPECT_TRUE(reports(diagnose(chunk("  PROC M()\n  ENDPROC\n", "")), Rule::duplicate_name, 7));
    EXPECT_TRUE(
        reports(diagnose(chunk("", "    VAR num a;\n    VAR num A;\n")), Rule::duplicate_name, 7));
}

TEST(RapidValidator, ModuleCount) {
    EXPECT_TRUE(reports(diagnose(chunk("", good_body()) + "MODULE N\nENDMODULE\n"),
                        Rule::module_count, 11));
    EXPECT_TRUE(reports(diagnose("  ! nothing here\n"), Rule::module_count, 0));
    EXPECT_TRUE(reports(diagnose(""), Rule::module_count, 0));
}

TEST(RapidValidator, ModuleName) {
    ValidateOptions o = validator_options();
    o.file_name = "/tmp/job/Print_0002.mod";
    EXPECT_TRUE(reports(diagnose(chunk("", good_body()), o), Rule::module_name, 1));
    o.file_name = "m.mod";  // case-insensitive, like RAPID names
    EXPECT_TRUE(diagnose(chunk("", good_body()), o).empty());
    o.check_module_name = false;
    o.file_name = "other.mod";
    EXPECT_TRUE(diagnose(chunk("", good_body()), o).empty());
    o = validator_options();
    o.loaded_modules = {"FcMain", "M"};
    EXPECT_TRUE(reports(diagnose(chunk("", good_body()), o), Rule::module_name, 1));
}

TEST(RapidValidator, ModuleAttributes) {
    EXPECT_TRUE(reports(diagnose("MODULE M(SYSMODULE, NOVIEW, VIEWONLY)\nENDMODULE\n"),
                        Rule::module_attribute, 1));
    EXPECT_TRUE(reports(diagnose("MODULE M(FAST)\nENDMODULE\n"), Rule::module_attribute, 1));
    EXPECT_TRUE(
        reports(diagnose("MODULE M(NOSTEPIN, NOSTEPIN)\nENDMODULE\n"), Rule::module_attribute, 1));
    EXPECT_TRUE(diagnose("MODULE M(SYSMODULE, NOSTEPIN, READONLY)\nENDMODULE\n").empty());
}

TEST(RapidValidator, DeclarationOrder) {
    const auto ds = diagnose(chunk("", "    Stop;\n    VAR num n;\n    n := 1;\n"));
    EXPECT_TRUE(reports(ds, Rule::declaration_order, 7));
    EXPECT_EQ(ds.size(), 1u) << indented_diagnostics(ds);  // n is still known to the statements after it
}

TEST(RapidValidator, Declaration) {
    EXPECT_TRUE(reports(diagnose(chunk("  CONST num c;\n", "")), Rule::declaration, 5));
    EXPECT_TRUE(reports(diagnose(chunk("  PERS triggdata tgX;\n", "")), Rule::declaration, 5));
    EXPECT_TRUE(reports(diagnose(chunk("  TASK VAR num x;\n", "")), Rule::declaration, 5));
    EXPECT_TRUE(reports(diagnose(chunk("", "    LOCAL VAR num x;\n")), Rule::declaration, 6));
    EXPECT_TRUE(reports(diagnose(chunk("  VAR num a{0};\n", "")), Rule::declaration, 5));
    EXPECT_TRUE(reports(diagnose(chunk("  VAR num a{9E9};\n", "")), Rule::declaration, 5));
    EXPECT_TRUE(diagnose(chunk("  TASK PERS num x := 1;\n  LOCAL VAR num y{3};\n", "")).empty());
}

TEST(RapidValidator, UnknownType) {
    EXPECT_TRUE(reports(diagnose(chunk("  VAR mytype x;\n", "")), Rule::unknown_type, 5));
}

TEST(RapidValidator, Undeclared) {
    EXPECT_TRUE(reports(diagnose(chunk("", "    MoveL p10, vPrint, fine, tNozzle;\n")),
                        Rule::undeclared, 6));
    EXPECT_TRUE(reports(diagnose(chunk("", "    PrintLayer;\n")), Rule::undeclared, 6));
    EXPECT_TRUE(reports(diagnose(chunk("", "    SetGO goOther, 1;\n")), Rule::undeclared, 6));
    EXPECT_TRUE(reports(diagnose(chunk("", "    TPWrite NoSuchFunc(1);\n")), Rule::undeclared, 6));
    EXPECT_TRUE(reports(diagnose(chunk("", "    TPWrite \"x\" \\Num:=vPrint.speed;\n")),
                        Rule::undeclared, 6));
    // Declared before use: module data initialisers see only the data above them.
    EXPECT_TRUE(reports(diagnose(chunk("  CONST num a := b;\n  CONST num b := 1;\n", "")),
                        Rule::undeclared, 5));
    // Signals, external routines and external data come from the options.
    ValidateOptions o = validator_options();
    o.external_routines = {"FcMain:GoSafe"};
    o.external_data = {{"nLayer", "num"}};
    EXPECT_TRUE(diagnose(chunk("", "    GoSafe;\n    Incr nLayer;\n"), o).empty());
    // A FOR variable exists inside its loop only.
    EXPECT_TRUE(reports(
        diagnose(chunk("", "    FOR i FROM 1 TO 3 DO\n    ENDFOR\n    TPWrite \"\" \\Num:=i;\n")),
        Rule::undeclared, 8));
}

TEST(RapidValidator, ArgumentCount) {
    EXPECT_TRUE(
        reports(diagnose(chunk("", "    MoveL " + std::string(target) + ", vPrint, fine;\n")),
                Rule::argument_count, 6));
    EXPECT_TRUE(reports(diagnose(chunk("  PROC Sub(num a)\n  ENDPROC\n", "    Sub;\n")),
                        Rule::argument_count, 8));
}

TEST(RapidValidator, OptionalArgument) {
    const std::string move = "    MoveL " + std::string(target) + ", vPrint, fine, tNozzle ";
    EXPECT_TRUE(
        reports(diagnose(chunk("", move + "\\Wobject:=wobj0;\n")), Rule::optional_argument, 6));
    EXPECT_TRUE(reports(diagnose(chunk("", move + "\\WObj;\n")), Rule::optional_argument, 6));
    EXPECT_TRUE(reports(diagnose(chunk("", "    TriggIO tgOn, 0 \\Start:=1 \\DOp:=goEvent, 1;\n")),
                        Rule::optional_argument, 6));
    EXPECT_TRUE(
        reports(diagnose(chunk("", "    ConfL \\Off \\Off;\n")), Rule::optional_argument, 6));
    EXPECT_TRUE(diagnose(chunk("",
                               "    StartLoad \\Dynamic, diskhome \\File:=\"a.mod\", ls;\n"
                               "    WaitLoad ls;\n"))
                    .size() == 2u);  // only ls undeclared
}

TEST(RapidValidator, ArgumentType) {
    // Speed and zone swapped.
    EXPECT_TRUE(reports(
        diagnose(chunk("", "    MoveL " + std::string(target) + ", fine, vPrint, tNozzle;\n")),
        Rule::argument_type, 6));
    EXPECT_TRUE(reports(diagnose(chunk("  VAR signaldi diLocal;\n", "    SetDO diLocal, 1;\n")),
                        Rule::argument_type, 7));
    EXPECT_TRUE(
        reports(diagnose(chunk("  VAR num n;\n", "    n := \"text\";\n")), Rule::argument_type, 7));
    EXPECT_TRUE(
        reports(diagnose(chunk("", "    WHILE 1 DO\n    ENDWHILE\n")), Rule::argument_type, 6));
}

TEST(RapidValidator, AggregateShape) {
    EXPECT_TRUE(reports(diagnose(chunk("  VAR speeddata vBad := [30,500,5000];\n", "")),
                        Rule::aggregate_shape, 5));
    EXPECT_TRUE(
        reports(diagnose(chunk("",
                               "    MoveL [[10,20,0.8],[0.000000,0.000000,1.000000,0.000000],"
                               "[0,0,-1,1]], vPrint, fine, tNozzle;\n")),
                Rule::aggregate_shape, 6));
    EXPECT_TRUE(
        reports(diagnose(chunk("  VAR num a{2} := [1,2,3];\n", "")), Rule::aggregate_shape, 5));
    EXPECT_TRUE(reports(diagnose(chunk("  VAR bool b := 1;\n", "")), Rule::aggregate_shape, 5));
}

TEST(RapidValidator, Initializer) {
    EXPECT_TRUE(reports(diagnose(chunk("  VAR num a := 1;\n  VAR num b := a;\n", "")),
                        Rule::initializer, 6));
    EXPECT_TRUE(
        reports(diagnose(chunk("  VAR num a := DInput(diReady);\n", "")), Rule::initializer, 5));
    EXPECT_TRUE(reports(diagnose(chunk("  VAR num a := 1 / 0;\n", "")), Rule::initializer, 5));
    EXPECT_TRUE(
        diagnose(chunk("  CONST num a := 2;\n  VAR num b := a * 3 + Abs(-1);\n", "")).empty());
}

TEST(RapidValidator, ConstAssignment) {
    EXPECT_TRUE(reports(diagnose(chunk("  CONST num c := 1;\n", "    c := 2;\n")),
                        Rule::const_assignment, 7));
    EXPECT_TRUE(
        reports(diagnose(chunk("", "    FOR i FROM 1 TO 3 DO\n      i := 2;\n    ENDFOR\n")),
                Rule::const_assignment, 7));
    EXPECT_TRUE(reports(diagnose(chunk("", "    v100.v_tcp := 2;\n")), Rule::const_assignment, 6));
}

TEST(RapidValidator, QuaternionNorm) {
    EXPECT_TRUE(reports(
        diagnose(chunk("  CONST robtarget p := [[0,0,0],[0.500000,0.500000,0.500000,0.600000],"
                       "[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n",
                       "")),
        Rule::quaternion_norm, 5));
    EXPECT_TRUE(reports(diagnose(chunk("  PERS tooldata tBent := [TRUE,[[0,0,100],[0.9,0,0,0]],"
                                       "[0.5,[0,0,50],[1,0,0,0],0,0,0]];\n",
                                       "")),
                        Rule::quaternion_norm, 5));
    EXPECT_TRUE(
        reports(diagnose(chunk("",
                               "    MoveL [[1,2,3],[0.000000,0.000000,0.990000,0.000000],"
                               "[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], vPrint, fine, tNozzle;\n")),
                Rule::quaternion_norm, 6));
    // Within 1e-5 after rounding to 6 decimals.
    EXPECT_TRUE(diagnose(chunk("  CONST orient q := [0.707107,0.000000,0.707107,0.000000];\n", ""))
                    .empty());
}

TEST(RapidValidator, QuaternionDigits) {
    const auto ds =
        diagnose(chunk("  CONST robtarget p := [[0,0,0],[0.707107,0.0,0.707107,0.000000],"
                       "[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n",
                       ""));
    EXPECT_TRUE(reports(ds, Rule::quaternion_digits, 5));
    EXPECT_EQ(ds.size(), 1u) << indented_diagnostics(ds);
    EXPECT_TRUE(reports(diagnose(chunk("  CONST orient q := [0.5,0.5,0.5,0.5];\n", "")),
                        Rule::quaternion_digits, 5));
    // Exponent form counts: 7.07107E-01 has 6 decimals; negative components are fine.
    EXPECT_TRUE(
        diagnose(chunk("  CONST orient q := [7.07107E-01,0,-7.07107E-01,0];\n", "")).empty());
}

TEST(RapidValidator, Speed) {
    EXPECT_TRUE(reports(diagnose(chunk("  VAR speeddata vStill := [0,500,5000,1000];\n", "")),
                        Rule::speed, 5));
    EXPECT_TRUE(reports(diagnose(chunk("", "    MoveL " + std::string(target) +
                                               ", [-5,500,5000,1000], fine, tNozzle;\n")),
                        Rule::speed, 6));
}

TEST(RapidValidator, ToolMassAndCog) {
    EXPECT_TRUE(reports(diagnose(chunk("  PERS tooldata tLight := [TRUE,[[0,0,100],[1,0,0,0]],"
                                       "[0,[0,0,50],[1,0,0,0],0,0,0]];\n",
                                       "")),
                        Rule::tool_mass, 5));
    const auto cog =
        diagnose(chunk("  PERS tooldata tFlat := [TRUE,[[0,0,100],[1,0,0,0]],"
                       "[0.5,[0,0,0],[1,0,0,0],0,0,0]];\n",
                       ""));
    ASSERT_TRUE(reports(cog, Rule::tool_cog, 5));
    EXPECT_EQ(cog[0].severity, Severity::warning);
    EXPECT_FALSE(has_errors(cog));
}

TEST(RapidValidator, TriggerSetup) {
    const std::string triggl =
        "    TriggL " + std::string(target) + ", vPrint, tgOn, z0, tNozzle;\n";
    // Used before the TriggIO that sets it up.
    EXPECT_TRUE(reports(diagnose(chunk("", triggl + "    TriggIO tgOn, 0 \\DOp:=goEvent, 1;\n")),
                        Rule::trigger_setup, 6));
    // \T2 never set up.
    EXPECT_TRUE(reports(
        diagnose(chunk("  VAR triggdata tgOff;\n",
                       "    TriggIO tgOn, 0 \\GOp:=goEvent, 1;\n"
                       "    TriggL " +
                           std::string(target) + ", vPrint, tgOn \\T2:=tgOff, z0, tNozzle;\n")),
        Rule::trigger_setup, 8));
    // Set up in another routine does not count.
    EXPECT_TRUE(
        reports(diagnose(chunk(
                    "  PROC Setup()\n    TriggIO tgOn, 0 \\GOp:=goEvent, 1;\n  ENDPROC\n", triggl)),
                Rule::trigger_setup, 9));
    // TriggEquip sets up as well.
    EXPECT_TRUE(
        diagnose(chunk("", "    TriggEquip tgOn, 0, 0.05 \\GOp:=goEvent, 1;\n" + triggl)).empty());
}

TEST(RapidValidator, LateCall) {
    EXPECT_TRUE(
        reports(diagnose(chunk("", "    %\"Print_0002:Print_0002\"%;\n")), Rule::late_call, 6));
    EXPECT_TRUE(reports(diagnose(chunk("", "    %\"a:b:c\"%;\n")), Rule::late_call, 6));
    ValidateOptions o = validator_options();
    o.external_routines = {"Print_0002:Print_0002"};
    EXPECT_TRUE(diagnose(chunk("", "    %\"Print_0002:Print_0002\"%;\n"), o).empty());
    EXPECT_TRUE(diagnose(chunk("  PROC Sub()\n  ENDPROC\n", "    %\"M:Sub\"%;\n")).empty());
    // A computed name is only checked for its names and type.
    EXPECT_TRUE(diagnose(chunk("  VAR string s := \"Sub\";\n", "    %s + \"x\"%;\n")).empty());
}

TEST(RapidValidator, ReadModuleThrowsTheFirstError) {
    try {
        read_module(chunk("  VAR num n := 1\n", ""), validator_options());
        FAIL() << "no throw";
    } catch (const RapidError& e) {
        EXPECT_EQ(e.rule(), Rule::syntax);
        EXPECT_EQ(e.line(), 6u);
        EXPECT_NE(std::string(e.what()).find("[syntax]"), std::string::npos);
    }
    ValidateOptions o = validator_options();
    o.file_name = "M.mod";
    EXPECT_NO_THROW(read_module(chunk("", good_body()), o));
    // Warnings do not throw.
    EXPECT_NO_THROW(read_module(chunk("  PERS tooldata tFlat := [TRUE,[[0,0,100],[1,0,0,0]],"
                                      "[0.5,[0,0,0],[1,0,0,0],0,0,0]];\n",
                                      ""),
                                o));
}
