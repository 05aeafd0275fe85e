// Runs a fuzz target's LLVMFuzzerTestOneInput over every file of the directories (or files) on
// the command line: the harnesses built with any compiler, their corpora replayed by CTest.
// A finding aborts (crash, sanitizer report, escaping exception); otherwise it exits 0.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

namespace fs = std::filesystem;

std::string read_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

void replay(const fs::path& file) {
    const std::string bytes = read_bytes(file);
    std::printf("replay %s (%zu bytes)\n", file.string().c_str(), bytes.size());
    std::fflush(stdout);  // the last name shows which input a crash came from
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

}  // namespace

int main(int argc, char** argv) {
    std::size_t inputs = 0;
    for (int i = 1; i < argc; ++i) {
        const fs::path arg(argv[i]);
        std::vector<fs::path> files;
        if (fs::is_directory(arg)) {
            for (const auto& entry : fs::directory_iterator(arg))
                if (entry.is_regular_file()) files.push_back(entry.path());
        } else if (fs::is_regular_file(arg)) {
            files.push_back(arg);
        } else {
            std::fprintf(stderr, "replay: %s is neither a file nor a directory\n", argv[i]);
            return 2;
        }
        std::sort(files.begin(), files.end());  // the same order on every machine
        for (const fs::path& f : files) replay(f);
        inputs += files.size();
    }
    if (inputs == 0) {
        std::fprintf(stderr, "replay: no inputs (an empty corpus?)\n");
        return 2;
    }
    std::printf("replay: %zu inputs, no finding\n", inputs);
    return 0;
}
