// Damaged files of every format: each must give a model or an InputError, never a crash, another
// exception or a sanitizer report. Truncation at every byte, and seeded random byte corruption.

#include "planner/io/msh_reader.hpp"
#include "planner/io/selection_reader.hpp"
#include "planner/io/stress_text_reader.hpp"
#include "planner/io/tet_reader.hpp"
#include "planner/io/vtk_reader.hpp"

#include "io_test_support.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <random>

using namespace fibrecell::planner;

namespace {

using Parser = std::function<void(std::string_view)>;

struct Case {
    const char* file;
    Parser parse;
};

const Case kCases[] = {
    {"cube.vtk", [](std::string_view t) { parse_vtk(t, "f.vtk"); }},
    {"cube_binary.vtk", [](std::string_view t) { parse_vtk(t, "f.vtk"); }},
    {"cube22.msh", [](std::string_view t) { parse_msh(t, "f.msh"); }},
    {"cube41.msh", [](std::string_view t) { parse_msh(t, "f.msh"); }},
    {"cube.tet", [](std::string_view t) { parse_tet_mesh(t, "f.tet"); }},
    {"cube_stress.txt", [](std::string_view t) { parse_stress_text(t, "f.txt", 6); }},
    {"cube_selection.txt", [](std::string_view t) { parse_selection(t, "f.txt", 8); }},
};

// True when `text` parses or is rejected with an InputError; anything else fails the test.
void parses_or_rejects(const Parser& parse, const std::string& text, const std::string& what) {
    try {
        parse(text);
    } catch (const InputError&) {
    } catch (const std::exception& e) {
        ADD_FAILURE() << what << ": unexpected exception " << e.what();
    }
}

}  // namespace

TEST(MalformedInput, EveryTruncationIsReadOrRejected) {
    for (const Case& c : kCases) {
        const std::string text = io_test::read_text(io_test::data_path(c.file));
        ASSERT_FALSE(text.empty()) << c.file;
        for (std::size_t n = 0; n < text.size(); ++n)
            parses_or_rejects(c.parse, text.substr(0, n),
                              std::string(c.file) + " cut at " + std::to_string(n));
    }
}

TEST(MalformedInput, RandomByteCorruptionIsReadOrRejected) {
    std::mt19937 rng(20240611);
    const std::string alphabet = "0123456789 \n\t.-+eE$\"#abcxyzNAIF\x01\xff";
    for (const Case& c : kCases) {
        const std::string text = io_test::read_text(io_test::data_path(c.file));
        for (int round = 0; round < 300; ++round) {
            std::string bad = text;
            const int edits = 1 + static_cast<int>(rng() % 4);
            for (int e = 0; e < edits; ++e) {
                const std::size_t at = rng() % bad.size();
                switch (rng() % 3) {
                    case 0:
                        bad[at] = alphabet[rng() % alphabet.size()];
                        break;
                    case 1:
                        bad.erase(at, 1 + rng() % 8);
                        break;
                    default:
                        bad.insert(at, 1, alphabet[rng() % alphabet.size()]);
                        break;
                }
                if (bad.empty()) bad = "x";
            }
            parses_or_rejects(c.parse, bad,
                              std::string(c.file) + " round " + std::to_string(round));
        }
    }
}
