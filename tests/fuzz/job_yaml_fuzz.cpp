// Feeds the bytes to the job YAML reader (planner/job/job_spec.hpp, parse_job) as a submitted
// job beside its files. A JobSpec or a ConfigError is the contract; anything else is a finding.
#include "config/yaml_section.hpp"
#include "planner/job/job_spec.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace {

namespace fs = std::filesystem;

// The folder a submitted job's files land in, with the files the seed jobs name.
class SubmittedFiles {
  public:
    SubmittedFiles() {
        std::string pattern = (fs::temp_directory_path() / "fibrecell-fuzz-job-XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr) std::abort();
        dir_ = pattern;
        for (const char* name : {"part.msh", "part.vtk", "part.tet", "part_stress.txt"})
            std::ofstream(dir_ / name) << "\n";
    }
    ~SubmittedFiles() {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    SubmittedFiles(const SubmittedFiles&) = delete;
    SubmittedFiles& operator=(const SubmittedFiles&) = delete;

    std::string dir() const { return dir_.string(); }

  private:
    fs::path dir_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const SubmittedFiles files;
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        fibrecell::planner::parse_job(text, "<job.submit>", files.dir(),
                                      fibrecell::planner::JobFiles::submitted_only);
    } catch (const fibrecell::config::ConfigError&) {
    }
    return 0;
}
