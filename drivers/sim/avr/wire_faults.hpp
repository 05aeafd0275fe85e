#pragma once
// Faults on one direction of the serial wire, byte by byte: a byte lost, a bit flipped, or one
// line in so many with one of its bytes flipped (what EMI on a long USB cable does). Seeded, so a
// failing run can be repeated.

#include <cstdint>
#include <optional>
#include <random>

namespace fibrecell::drivers::sim::avr {

struct WireFaultRates {
    double drop_byte = 0;    // probability that a byte is lost
    double flip_byte = 0;    // probability that a byte has one bit flipped
    double corrupt_line = 0; // probability that a line (up to '\n') gets one byte flipped, the
                             // line staying one line (a flip into '\n' or '\r' is not made)
};

struct WireFaultCounts {
    std::uint64_t bytes = 0, dropped = 0, flipped = 0, lines_corrupted = 0;
};

class WireFaults {
  public:
    explicit WireFaults(std::uint32_t seed = 1) : rng_(seed) {}

    void set(const WireFaultRates& rates) { rates_ = rates; }
    const WireFaultRates& rates() const { return rates_; }
    const WireFaultCounts& counts() const { return counts_; }

    // The byte as it arrives at the other end, or nothing when it is lost.
    std::optional<std::uint8_t> pass(std::uint8_t byte);

  private:
    bool chance(double p) { return p > 0 && std::uniform_real_distribution<double>(0, 1)(rng_) < p; }
    // One bit of the 7 low ones flipped; `keep_line`: never into a line end.
    std::uint8_t flip(std::uint8_t byte, bool keep_line);

    std::mt19937 rng_;
    WireFaultRates rates_;
    WireFaultCounts counts_;
    int line_flip_at_ = -1;  // the position in the current line to flip; -1: none
    int line_pos_ = 0;
};

}  // namespace fibrecell::drivers::sim::avr
