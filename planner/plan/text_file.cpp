#include "planner/plan/text_file.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace fibrecell::planner {

void write_text_file(const std::string& path, const std::string& text) {
    const std::string tmp = path + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary);
        out << text;
        if (!out.flush()) throw std::runtime_error(tmp + ": cannot write");
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        std::remove(tmp.c_str());
        throw std::runtime_error(path + ": cannot replace the file");
    }
}

}  // namespace fibrecell::planner
