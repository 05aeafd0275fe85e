#pragma once
// Helpers for the reader tests: a temporary directory for files written by a test, and a check
// that a call is rejected with an InputError whose message names what it should.

#include "planner/input_error.hpp"
#include "planner/mesh/tet_mesh.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/project_paths.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace io_test {

// The unit cube of the test data: vertex i = (i&1, i>>1&1, i>>2&1), six positive tets.
inline const std::vector<fibrecell::planner::Tet> kCubeTets = {
    {0, 1, 3, 7}, {0, 5, 1, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 6, 4, 7}};

inline std::string data_path(const std::string& name) {
    return fibrecell::test::test_data_path("io/") + name;
}

inline std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// A fresh directory removed with its contents at the end of the test.
using TempDir = fibrecell::test::TempDir;

// `text` with the first occurrence of `from` replaced by `to`; fails the test if absent.
inline std::string replaced(std::string text, std::string_view from, std::string_view to) {
    const auto at = text.find(from);
    if (at == std::string::npos) {
        ADD_FAILURE() << "test setup: '" << from << "' not found";
        return text;
    }
    return text.replace(at, from.size(), to);
}

// Runs `f`, requires an InputError whose message contains every part; returns the message.
template <class F>
std::string rejection(F&& f, std::initializer_list<std::string_view> parts) {
    try {
        f();
    } catch (const fibrecell::planner::InputError& e) {
        const std::string message = e.what();
        for (std::string_view part : parts)
            EXPECT_NE(message.find(part), std::string::npos)
                << "message lacks '" << part << "': " << message;
        return message;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "expected InputError, got another exception: " << e.what();
        return {};
    }
    ADD_FAILURE() << "expected InputError, nothing thrown";
    return {};
}

#define EXPECT_REJECTED(statement, ...)                                  \
    do {                                                                 \
        SCOPED_TRACE(#statement);                                        \
        ::io_test::rejection([&] { (void)(statement); }, {__VA_ARGS__}); \
    } while (0)

// The stress the test data gives tet i (same formula as in the data files).
inline fibrecell::planner::StressTensor cube_stress(int i) {
    const double xy = 1 + 0.5 * i, xz = 2 + 0.25 * i, yz = 3 + 0.125 * i;
    fibrecell::planner::StressTensor s;
    s << 10 + i, xy, xz, xy, 20 + i, yz, xz, yz, 30 + i;
    return s;
}

// Every tet positively oriented.
inline bool all_positive(const fibrecell::planner::TetMesh& mesh) {
    for (const auto& t : mesh.tets)
        if (!(fibrecell::planner::signed_volume(mesh, t) > 0)) return false;
    return true;
}

}  // namespace io_test
