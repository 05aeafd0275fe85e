#pragma once
// A folder of its own for one test or fixture: made unique under the system's temporary folder
// (mkdtemp), removed with everything in it when the object goes, unless keep() was called (a
// failed service test keeps its logs).

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>

namespace fibrecell::test {

// The whole file as bytes ("" when it cannot be read).
inline std::string read_file(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

class TempDir {
  public:
    // <tmp>/fibrecell-<prefix>-XXXXXX, empty.
    explicit TempDir(std::string_view prefix = "test") {
        std::string pattern = (std::filesystem::temp_directory_path() /
                               ("fibrecell-" + std::string(prefix) + "-XXXXXX"))
                                  .string();
        if (!::mkdtemp(pattern.data()))
            throw std::system_error(errno, std::generic_category(), "mkdtemp " + pattern);
        path_ = pattern;
    }
    ~TempDir() {
        if (kept_) return;
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path path(const std::filesystem::path& name) const { return path_ / name; }
    std::filesystem::path operator/(const std::filesystem::path& name) const { return path_ / name; }
    operator const std::filesystem::path&() const { return path_; }  // NOLINT: a folder is a path
    std::string string() const { return path_.string(); }

    // Writes `content` to `name` in the folder (its parent folders made) and returns its path.
    std::filesystem::path write(const std::filesystem::path& name, std::string_view content) const {
        const auto file = path_ / name;
        std::filesystem::create_directories(file.parent_path());
        std::ofstream out(file, std::ios::binary);
        out.write(content.data(), static_cast<std::streamsize>(content.size()));
        if (!out) throw std::runtime_error("cannot write " + file.string());
        return file;
    }

    // The folder stays after the object goes (its path is printed by the caller).
    void keep() { kept_ = true; }

  private:
    std::filesystem::path path_;
    bool kept_ = false;
};

}  // namespace fibrecell::test
