// Faults on the wire: none by default, the configured rates, one byte per corrupted line, and
// the same faults again for the same seed.
#include "drivers/sim/avr/wire_faults.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace fibrecell::drivers::sim::avr;

namespace {

std::string send(WireFaults& w, const std::string& bytes) {
    std::string out;
    for (char c : bytes)
        if (const auto b = w.pass(static_cast<std::uint8_t>(c))) out.push_back(static_cast<char>(*b));
    return out;
}

std::string lines(int n) {
    std::string s;
    for (int i = 0; i < n; ++i) s += "N" + std::to_string(i) + " G1 E0.50000 F300.0*85\n";
    return s;
}

}  // namespace

TEST(WireFaults, PassesEverythingUntilTold) {
    WireFaults w;
    const std::string s = lines(200);
    EXPECT_EQ(send(w, s), s);
    EXPECT_EQ(w.counts().bytes, s.size());
}

TEST(WireFaults, DropsAndFlipsAtTheirRates) {
    WireFaults w(7);
    w.set({.drop_byte = 0.01});
    const std::string s(200'000, 'G');
    const std::string out = send(w, s);
    EXPECT_EQ(s.size() - out.size(), w.counts().dropped);
    EXPECT_NEAR(static_cast<double>(w.counts().dropped), 2000, 200);  // ~4.5 sigma
    w.set({.flip_byte = 0.01});
    const std::string flipped = send(w, s);
    std::size_t differ = 0;
    for (char c : flipped) differ += c != 'G';
    EXPECT_EQ(differ, w.counts().flipped);
    EXPECT_NEAR(static_cast<double>(differ), 2000, 200);
}

TEST(WireFaults, ACorruptedLineHasExactlyOneByteChanged) {
    WireFaults w(3);
    w.set({.corrupt_line = 0.25});
    const std::string s = lines(400);
    const std::string out = send(w, s);
    ASSERT_EQ(out.size(), s.size());
    std::size_t changed_lines = 0, pos = 0;
    while (pos < s.size()) {
        const std::size_t end = s.find('\n', pos);
        std::size_t diff = 0;
        for (std::size_t i = pos; i <= end; ++i) diff += s[i] != out[i];
        EXPECT_LE(diff, 1u);
        changed_lines += diff;
        pos = end + 1;
    }
    EXPECT_EQ(changed_lines, w.counts().lines_corrupted);
    EXPECT_NEAR(static_cast<double>(changed_lines), 100, 30);
}

TEST(WireFaults, TheSameSeedGivesTheSameFaults) {
    WireFaults a(11), b(11);
    a.set({.drop_byte = 0.05, .flip_byte = 0.05});
    b.set({.drop_byte = 0.05, .flip_byte = 0.05});
    const std::string s = lines(100);
    EXPECT_EQ(send(a, s), send(b, s));
}
