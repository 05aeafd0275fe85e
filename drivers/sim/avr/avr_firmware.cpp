#include "drivers/sim/avr/avr_firmware.hpp"

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace fibrecell::drivers::sim::avr {

FirmwareImage::~FirmwareImage() {
    if (chunks) {
        free_ihex_chunks(chunks);  // 1.6 frees the chunks' data, not their array
        std::free(chunks);
        return;  // the flash pointer was one of the chunks'
    }
    for (std::uint32_t i = 0; f.symbol && i < f.symbolcount; ++i) std::free(f.symbol[i]);
    for (void* p : {static_cast<void*>(f.symbol), static_cast<void*>(f.flash),
                    static_cast<void*>(f.eeprom), static_cast<void*>(f.fuse),
                    static_cast<void*>(f.lockbits)})
        std::free(p);
}

void read_firmware(const std::string& path, FirmwareImage& image) {
    namespace fs = std::filesystem;
    if (!fs::is_regular_file(path)) throw std::runtime_error("gt2560-avr: no firmware file " + path);
    elf_firmware_t& f = image.f;
    const std::string ext = fs::path(path).extension().string();
    if (ext == ".hex" || ext == ".ihex") {
        ihex_chunk_p& chunks = image.chunks;
        const int n = read_ihex_chunks(path.c_str(), &chunks);
        if (n <= 0) throw std::runtime_error("gt2560-avr: " + path + " is not an Intel HEX file");
        for (int i = 0; i < n; ++i) {
            if (chunks[i].baseaddr >= AVR_SEGMENT_OFFSET_EEPROM) continue;  // EEPROM left blank
            if (f.flash) throw std::runtime_error("gt2560-avr: " + path + " has several flash chunks");
            f.flash = chunks[i].data;
            f.flashsize = chunks[i].size;
            f.flashbase = chunks[i].baseaddr;
        }
        if (!f.flash) throw std::runtime_error("gt2560-avr: " + path + " has no flash data");
    } else if (elf_read_firmware(path.c_str(), &f) != 0) {
        throw std::runtime_error("gt2560-avr: " + path + " is not an AVR ELF file");
    }
    if (f.mmcu[0] && std::string(f.mmcu) != "atmega2560")
        throw std::runtime_error("gt2560-avr: " + path + " is built for " + f.mmcu +
                                 ", the GT2560 has an atmega2560");
    if (f.flashbase + f.flashsize > 256 * 1024)
        throw std::runtime_error("gt2560-avr: " + path + " does not fit the 256 KiB flash");
}

void retire_core(avr_t* core) {
    static auto* cores = new std::vector<avr_t*>;  // never destroyed: reachable at exit
    cores->push_back(core);
}

}  // namespace fibrecell::drivers::sim::avr
