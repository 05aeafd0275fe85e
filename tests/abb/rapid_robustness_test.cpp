// Malformed input never crashes or hangs the reader: it yields diagnostics or a model. Truncations
// at every byte of a good chunk and byte flips with a fixed seed; plus a few hostile inputs.

#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "drivers/abb/rapid/reader.hpp"
#include "tests/support/project_paths.hpp"

using namespace fibrecell::drivers::abb::rapid;

namespace {

std::string read_file(const std::string& name) {
    std::ifstream in(fibrecell::test::test_data_path("rapid/") + name, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

ValidateOptions options() {
    ValidateOptions o;
    o.known_signals = {"goEvent", "diExtruderReady", "diJobReady", "diAbort"};
    return o;
}

// The reader's promise: a model, or at least one error. Also exercises the model's consumers.
// Returns whether there was an error.
bool check_never_crashes(const std::string& text) {
    const CheckResult r = check_module(text, options());
    EXPECT_TRUE(r.module || has_errors(r.diagnostics)) << "no model and no error for:\n" << text;
    for (const Diagnostic& d : r.diagnostics) EXPECT_FALSE(d.message.empty());
    if (r.module) (void)move_targets(*r.module);
    return has_errors(r.diagnostics);
}

}  // namespace

TEST(RapidRobustness, TruncationAtEveryByte) {
    const std::string text = read_file("Print_0001.mod");
    ASSERT_GT(text.size(), 1000u);
    // Every byte of the header and the first declarations, then every 11th byte (fast under ASan).
    for (std::size_t n = 0; n < text.size(); n += n < 500 ? 1 : 11) {
        SCOPED_TRACE("truncated at " + std::to_string(n));
        const bool error = check_never_crashes(text.substr(0, n));
        // Cut before ENDMODULE: the module is incomplete, which must be an error.
        if (n + 12 < text.size()) {
            EXPECT_TRUE(error);
        }
    }
}

TEST(RapidRobustness, RandomByteFlips) {
    const std::string sources[] = {read_file("Print_0001.mod"), read_file("FcMain.mod")};
    std::mt19937 rng(20240611);
    for (int i = 0; i < 300; ++i) {
        std::string text = sources[i % 2];
        std::uniform_int_distribution<std::size_t> where(0, text.size() - 1);
        std::uniform_int_distribution<int> byte(0, 255), count(1, 4);
        for (int k = count(rng); k > 0; --k) text[where(rng)] = static_cast<char>(byte(rng));
        SCOPED_TRACE("case " + std::to_string(i));
        check_never_crashes(text);
    }
}

TEST(RapidRobustness, HostileInputs) {
    const std::string hostile[] = {
        std::string(100000, '('),
        "MODULE M\n  CONST num n := " + std::string(50000, '-') + "1;\nENDMODULE\n",
        "MODULE M\n  CONST num n := " + std::string(50000, '[') + ";\nENDMODULE\n",
        "MODULE M\n  VAR num a{9E9, 9E9};\nENDMODULE\n",
        "MODULE M\n  VAR num a{100000000000000000000000000000} := 1;\nENDMODULE\n",
        "MODULE M\n  CONST num n := 1E999;\nENDMODULE\n",
        "MODULE M\n  CONST string s := NumToStr(1E300, 15);\nENDMODULE\n",
        "MODULE M\n  CONST num n := Round(1E300 \\Dec:=15) + 7 DIV 0.5 + 1E300 MOD 3;\nENDMODULE\n",
        "MODULE M\n  CONST string s := StrPart(\"abc\", 2, 1E9);\nENDMODULE\n",
        "MODULE M\n  CONST robtarget p := "
        "Offs([[1,2,3],[1,0,0,0],[1E300,0,0,0],[0,0,0,0,0,0]],1,2,3);\nENDMODULE\n",
        "%%%\n  VERSION:1\n",
        "MODULE M\n  PROC M()\n" + std::string(5000, ';') + "\n  ENDPROC\nENDMODULE\n",
        "MODULE M\n  PROC M()\n    %%;\n    %\"\"%;\n  ENDPROC\nENDMODULE\n",
        std::string("MODULE M\0\n", 10),
        "MODULE M\n  PROC M()\n    IF TRUE Stop\n  ENDPROC\nENDMODULE\n",
        "MODULE M\n  CONST num a{2,2} := [[1,2],[3,4]];\n  CONST num b := a{3,1} + "
        "a{1};\nENDMODULE\n",
    };
    for (const std::string& text : hostile) check_never_crashes(text);
}

TEST(RapidRobustness, LongChunkIsCounted) {
    // A chunk of inline-robtarget moves at the line limit (500 here to keep the test fast under
    // the sanitizers; the default limit is 5000): reports line-count only once it is passed.
    ValidateOptions o = options();
    o.max_lines = 500;
    std::string text = "MODULE Big\n  PROC Big()\n";
    for (int i = 0; i < 496; ++i)
        text += "    MoveL [[" + std::to_string(i) +
                ".000000,0,10],[0.000000,0.000000,1.000000,0.000000],[0,0,-1,1],"
                "[9E9,9E9,9E9,9E9,9E9,9E9]], v100, z0, tool0;\n";
    const std::string closing = "  ENDPROC\nENDMODULE\n";
    const CheckResult ok = check_module(text + closing, o);
    EXPECT_TRUE(ok.ok());
    EXPECT_EQ(ok.module->line_count, 500u);
    EXPECT_EQ(move_targets(*ok.module).size(), 496u);
    const CheckResult over = check_module(text + "    Stop;\n" + closing, o);
    ASSERT_EQ(over.diagnostics.size(), 1u);
    EXPECT_EQ(over.diagnostics[0].rule, Rule::line_count);
    EXPECT_EQ(over.diagnostics[0].line, 501u);
}
