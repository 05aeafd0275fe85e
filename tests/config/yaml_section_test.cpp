#include "config/yaml_section.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>

using fibrecell::config::ConfigError;
using fibrecell::config::Section;
using ::testing::HasSubstr;

namespace {

// Runs `read` on the text and returns the error message it throws ("" if none).
template <class F>
std::string error_of(const std::string& text, F read) {
    try {
        Section s = Section::load_text(text, "cell.yaml");
        read(s);
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(YamlSection, ReadsTypedValuesWithDefaults) {
    Section s = Section::load_text("a: 3\nb: 2.5\nc: text\nd: [1, 2, 3]\ne: {x: true}\n", "t.yaml");
    EXPECT_EQ(s.get<int>("a"), 3);
    EXPECT_DOUBLE_EQ(s.number("b", 0, 0, 10), 2.5);
    EXPECT_EQ(s.get<std::string>("c"), "text");
    EXPECT_EQ(s.vec3("d")[2], 3.0);
    Section e = s.section("e");
    EXPECT_TRUE(e.get<bool>("x"));
    EXPECT_EQ(e.get_or<int>("missing", 9), 9);
    EXPECT_NO_THROW(e.finish());
    EXPECT_NO_THROW(s.finish());
}

TEST(YamlSection, UnknownKeyNamesItsPathAndLine) {
    const auto msg = error_of("planner:\n  mu: 3\n  muu: 4\n", [](Section& s) {
        Section p = s.section("planner");
        p.get<int>("mu");
        p.finish();
    });
    EXPECT_THAT(msg, HasSubstr("cell.yaml: line 3: planner.muu: unknown key"));
}

TEST(YamlSection, OutOfBoundsNamesKeyRangeAndValue) {
    const auto msg = error_of("planner:\n  eta: 1.5\n",
                              [](Section& s) { s.section("planner").number("eta", 0.5, -1, 1); });
    EXPECT_THAT(msg, HasSubstr("line 2: planner.eta: must be in [-1, 1], got 1.5"));
}

TEST(YamlSection, WrongTypeAndMissingRequired) {
    EXPECT_THAT(error_of("a: hello\n", [](Section& s) { s.get<double>("a"); }),
                HasSubstr("a: must be a number, not 'hello'"));
    EXPECT_THAT(error_of("a: 1\n", [](Section& s) { s.get<std::string>("b"); }),
                HasSubstr("b: is required"));
    EXPECT_THAT(error_of("a: [1, 2]\n", [](Section& s) { s.vec3("a"); }),
                HasSubstr("a: must be a list of 3 numbers"));
    // A bad element of a list is named by its place, not "not a list".
    EXPECT_THAT(error_of("l: [3, 1e21]\n", [](Section& s) { s.get<std::vector<int>>("l"); }),
                HasSubstr("line 1: l[1]: must be a whole number, not '1e21'"));
    EXPECT_THAT(error_of("p:\n  l: [1, [2]]\n",
                         [](Section& s) { s.section("p").get<std::vector<double>>("l"); }),
                HasSubstr("p.l[1]: must be a number, not a list"));
    EXPECT_THAT(error_of("l: 4\n", [](Section& s) { s.get<std::vector<int>>("l"); }),
                HasSubstr("l: must be a list of whole numbers, not '4'"));
    EXPECT_THAT(error_of("a: .nan\n", [](Section& s) { s.get<double>("a"); }),
                HasSubstr("a: must be a finite number"));
    EXPECT_THAT(error_of("s: 5\n", [](Section& s) { s.section("s"); }),
                HasSubstr("s: must be a mapping"));
    EXPECT_THAT(error_of("k: maybe\n",
                         [](Section& s) {
                             s.choice("k", "yes", {"yes", "no"});
                         }),
                HasSubstr("k: must be one of yes, no, got 'maybe'"));
}

TEST(YamlSection, AKeyThatIsNotAPlainNameIsAnErrorWithItsLine) {
    // Found by the job YAML fuzz target: a list as a key threw yaml-cpp's bad conversion.
    EXPECT_THAT(error_of("a: 1\nplanner: {[1]: 2}\n", [](Section& s) { s.section("planner"); }),
                HasSubstr("cell.yaml: line 2: planner: a key must be a plain name, not a list"));
    EXPECT_THAT(error_of("{a: 1}: 2\n", [](Section&) {}),
                HasSubstr("document: a key must be a plain name, not a mapping"));
}

TEST(YamlSection, SyntaxErrorNamesLine) {
    EXPECT_THAT(error_of("a: 1\nb: [1, 2\n", [](Section&) {}), HasSubstr("cell.yaml: line"));
    EXPECT_THAT(error_of("- just\n- a list\n", [](Section&) {}), HasSubstr("must be a mapping"));
}

TEST(YamlSection, PathsAreAbsoluteOrInTheHomeDirectory) {
    const char* home = std::getenv("HOME");
    ASSERT_NE(home, nullptr);
    Section s = Section::load_text("a: ~/.local/state/x\nb: /var/lib/x\nc: \"~\"\n", "t.yaml");
    EXPECT_EQ(s.path_or("a", ""), std::string(home) + "/.local/state/x");
    EXPECT_EQ(s.path_or("b", ""), "/var/lib/x");
    EXPECT_EQ(s.path_or("c", ""), home);
    EXPECT_EQ(s.path_or("absent", "/run/x"), "/run/x");
    EXPECT_THAT(error_of("a: run/x\n", [](Section& t) { t.path_or("a", ""); }),
                HasSubstr("line 1: a: must be an absolute path (or start with ~/), got 'run/x'"));
    EXPECT_THAT(error_of("a: ~other/x\n", [](Section& t) { t.path_or("a", ""); }),
                HasSubstr("a: must be an absolute path"));
}

// YAML allows a key once per mapping; yaml-cpp would keep the first silently.
TEST(YamlSection, AKeyTwiceInOneMappingIsRefusedWithBothLines) {
    const auto nothing = [](Section&) {};
    EXPECT_EQ(error_of("a: 1\nb: 2\na: 3\n", nothing),
              "cell.yaml: line 3: a: the key appears twice in one mapping (first at line 1)");
    EXPECT_EQ(error_of("print:\n  x: 1\n  y: 2\n  x: 2\n", nothing),
              "cell.yaml: line 4: print.x: the key appears twice in one mapping (first at line 2)");
    EXPECT_EQ(error_of("loads:\n  - {f: 1, f: 2}\n", nothing),
              "cell.yaml: line 2: loads[0].f: the key appears twice in one mapping (first at line 2)");
    EXPECT_EQ(error_of("a: {x: 1}\nb: {x: 1}\n", nothing), "");  // the same key in two mappings
}

// Aliases that expand to billions of values ("billion laughs") are refused before anything
// walks them.
TEST(YamlSection, ADocumentThatExpandsBeyondAnyConfigurationIsRefused) {
    std::string bomb = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
    for (int i = 1; i <= 8; ++i)
        bomb += "a" + std::to_string(i) + ": &a" + std::to_string(i) + " [*a" + std::to_string(i - 1) +
                std::string(", *a") + std::to_string(i - 1) + ", *a" + std::to_string(i - 1) + ", *a" +
                std::to_string(i - 1) + ", *a" + std::to_string(i - 1) + ", *a" + std::to_string(i - 1) +
                ", *a" + std::to_string(i - 1) + ", *a" + std::to_string(i - 1) + ", *a" +
                std::to_string(i - 1) + ", *a" + std::to_string(i - 1) + "]\n";
    EXPECT_EQ(error_of(bomb, [](Section&) {}),
              "cell.yaml: more than 100000 values (aliases that expand?)");
}
