#include "drivers/sim/avr/wire_faults.hpp"

namespace fibrecell::drivers::sim::avr {

std::uint8_t WireFaults::flip(std::uint8_t byte, bool keep_line) {
    ++counts_.flipped;
    for (;;) {
        const auto out = static_cast<std::uint8_t>(byte ^ (1u << std::uniform_int_distribution<int>(0, 6)(rng_)));
        if (!keep_line || (out != '\n' && out != '\r')) return out;
    }
}

std::optional<std::uint8_t> WireFaults::pass(std::uint8_t byte) {
    ++counts_.bytes;
    if (line_pos_ == 0 && chance(rates_.corrupt_line)) {
        // A position within the first 12 bytes, where every line has something to flip; a line
        // shorter than that ends first and is left alone (lines_corrupted counts real flips).
        line_flip_at_ = std::uniform_int_distribution<int>(0, 11)(rng_);
    }
    const bool line_end = byte == '\n';
    const bool flip_here = line_pos_ == line_flip_at_ && !line_end;
    line_pos_ = line_end ? 0 : line_pos_ + 1;
    if (line_end) line_flip_at_ = -1;
    if (chance(rates_.drop_byte)) {
        ++counts_.dropped;
        return std::nullopt;
    }
    if (flip_here) {
        line_flip_at_ = -1;
        ++counts_.lines_corrupted;
        return flip(byte, true);
    }
    if (chance(rates_.flip_byte)) return flip(byte, false);
    return byte;
}

}  // namespace fibrecell::drivers::sim::avr
