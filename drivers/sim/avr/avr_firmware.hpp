#pragma once
// An ATmega2560 firmware image read for simavr (ELF or Intel HEX), with the checks a user's build
// deserves: the file is there, it is an AVR image, for this MCU, and fits its flash. Part of the
// board simulator (avr_board.cpp); it exposes simavr's types, so only the simulator includes it.

#include <sim_avr.h>
#include <sim_elf.h>
#include <sim_hex.h>

#include <string>

namespace fibrecell::drivers::sim::avr {

// The image's buffers, freed when it goes; keep it while a core runs it (the core may point at
// its symbols).
struct FirmwareImage {
    elf_firmware_t f{};
    ihex_chunk_p chunks = nullptr;
    FirmwareImage() = default;
    FirmwareImage(const FirmwareImage&) = delete;
    FirmwareImage& operator=(const FirmwareImage&) = delete;
    ~FirmwareImage();
};

// Reads `path` into `image`; throws std::runtime_error naming the file and what is wrong with it.
void read_firmware(const std::string& path, FirmwareImage& image);

// simavr 1.6 has no call that frees a core (avr_terminate frees its memories, not the core and
// its IRQs): a stopped core is kept here, reachable, for the rest of the process.
void retire_core(avr_t* core);

}  // namespace fibrecell::drivers::sim::avr
