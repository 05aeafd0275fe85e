#include "planner/io/file_text.hpp"

#include "planner/input_error.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

namespace fibrecell::planner {

std::string read_file_text(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError(path, "", "is a directory, not a file");

    struct Closer {
        void operator()(std::FILE* f) const { std::fclose(f); }
    };
    const std::unique_ptr<std::FILE, Closer> file(std::fopen(path.c_str(), "rb"));
    if (!file) throw InputError(path, "", std::string("cannot open: ") + std::strerror(errno));

    // Grow by chunks rather than trusting a size query: works for pipes and files that change.
    std::string text;
    const auto size_hint = std::filesystem::file_size(path, ec);
    if (!ec) text.reserve(size_hint + 1);
    constexpr std::size_t kChunk = 1 << 20;
    std::size_t used = 0;
    for (;;) {
        text.resize(used + kChunk);
        const std::size_t got = std::fread(text.data() + used, 1, kChunk, file.get());
        used += got;
        if (got < kChunk) break;
    }
    if (std::ferror(file.get())) throw InputError(path, "", "read error");
    text.resize(used);
    return text;
}

}  // namespace fibrecell::planner
