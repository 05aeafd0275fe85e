// Feeds the bytes to the service's planning as a submitted job: a job YAML and its VTK mesh
// (part.vtk), split at a line "%%%%" (no such line: all YAML, an empty mesh), planned by plan_job
// for the default cell into a scratch folder. The job planned, or refused with an exception
// (the job fails, the service goes on), is the contract; a crash, a hang (-timeout) or an
// allocation beyond -rss_limit_mb is a finding: work and memory must stay bounded by the part's
// physical size, whatever the file claims (docs/service.md, "Size limits").
#include "daemon/jobs/plan_job.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace {

namespace fs = std::filesystem;

class Scratch {
  public:
    Scratch() {
        std::string pattern = (fs::temp_directory_path() / "fibrecell-fuzz-plan-XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr) std::abort();
        dir_ = pattern;
    }
    ~Scratch() {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;
    const fs::path& dir() const { return dir_; }

  private:
    fs::path dir_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const Scratch scratch;
    const std::string text(reinterpret_cast<const char*>(data), size);
    const auto split = text.find("\n%%%%\n");
    std::ofstream(scratch.dir() / "job.yaml") << text.substr(0, split);
    std::ofstream(scratch.dir() / "part.vtk")
        << (split == std::string::npos ? std::string() : text.substr(split + 6));
    std::error_code ec;
    fs::remove_all(scratch.dir() / "plan", ec);
    fibrecell::daemon::jobs::PlanRequest request;
    request.job_file = scratch.dir() / "job.yaml";
    request.out_dir = scratch.dir() / "plan";
    request.mechanics = false;  // its own FEA: covered by the planner's tests, and slow here
    try {
        fibrecell::daemon::jobs::plan_job(request, {});
    } catch (const std::exception&) {
        // Refused or failed: the job's reason, as the service reports it.
    }
    return 0;
}
