#include "planner/io/text_scanner.hpp"

#include "planner/io/number_parse.hpp"

#include "io_test_support.hpp"

#include <gtest/gtest.h>

using namespace fibrecell::planner;

TEST(NumberParse, WholeTokensOnly) {
    EXPECT_EQ(parse_integer("42"), 42);
    EXPECT_EQ(parse_integer("+7"), 7);
    EXPECT_EQ(parse_integer("-3"), -3);
    EXPECT_FALSE(parse_integer("4.0"));
    EXPECT_FALSE(parse_integer("+-3"));
    EXPECT_FALSE(parse_integer(""));
    EXPECT_FALSE(parse_integer("99999999999999999999"));
    EXPECT_EQ(parse_real("1.5e-3"), 1.5e-3);
    EXPECT_EQ(parse_real("+2"), 2.0);
    EXPECT_EQ(parse_real("-0.25"), -0.25);
    EXPECT_FALSE(parse_real("1.5x"));
    EXPECT_FALSE(parse_real("1e999"));
    EXPECT_FALSE(parse_real("."));
}

TEST(TextScanner, TracksLinesAcrossTokensAndBlankLines) {
    TextScanner s("a b\r\n\n  c\n\td", "f.txt");
    EXPECT_EQ(s.token("x"), "a");
    EXPECT_EQ(s.line(), 1u);
    EXPECT_EQ(s.token("x"), "b");
    EXPECT_EQ(s.token("x"), "c");
    EXPECT_EQ(s.line(), 3u);
    EXPECT_EQ(s.peek(), "d");
    EXPECT_EQ(s.token("x"), "d");
    EXPECT_EQ(s.line(), 4u);
    EXPECT_TRUE(s.at_end());
    EXPECT_REJECTED(s.token("a keyword"),
                    "f.txt: line 4: unexpected end of file: expected a keyword");
}

TEST(TextScanner, NumbersAndErrorsNameTheLine) {
    TextScanner s("1 2.5\nnan x\n7", "f.txt");
    EXPECT_EQ(s.integer("n"), 1);
    EXPECT_EQ(s.real("v"), 2.5);
    EXPECT_REJECTED(s.real("a coordinate"), "f.txt: line 2: a coordinate is not a finite number");
    EXPECT_REJECTED(s.integer("a count"), "line 2: expected a count (an integer), found 'x'");
    EXPECT_REJECTED(s.integer("a count", 0, 5), "line 3: a count 7 is outside 0..5");
}

TEST(TextScanner, BinaryBlocksFollowTheHeaderLine) {
    const std::string text = std::string("HEAD 3  \n") + "\n\x01\x02" + "\nNEXT";
    TextScanner s(text, "b.vtk");
    s.expect("head");
    EXPECT_EQ(s.integer("n"), 3);
    s.end_header_line();
    EXPECT_EQ(s.bytes(3, "block"), std::string_view("\n\x01\x02", 3));
    EXPECT_EQ(s.token("x"), "NEXT");
    EXPECT_EQ(s.line(), 4u);  // the block's newline counts, as an editor would show it
    EXPECT_REJECTED(s.bytes(1, "CELLS"), "line 4: file ends inside the binary CELLS");
}

TEST(TextScanner, CountsAreCheckedAgainstTheFileSize) {
    TextScanner s("5\n1 2 3 4 5", "c.txt");
    const long long n = s.integer("n");
    s.check_count(n, 2, "value");
    EXPECT_REJECTED(s.check_count(6, 2, "value"), "line 1: value count 6 is more than");
    EXPECT_REJECTED(s.check_count(-1, 2, "value"), "negative value count -1");
}

TEST(TextScanner, QuotedStringsAndLines) {
    TextScanner s("2 1 \"my group\"\n\"open\nrest of line\n", "q.msh");
    s.skip_tokens(2, "x");
    EXPECT_EQ(s.quoted("a name"), "my group");
    EXPECT_REJECTED(s.quoted("a name"), "line 2: unterminated quoted a name");
}
