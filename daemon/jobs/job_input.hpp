#pragma once
// A job as submitted (job.submit): the job YAML text and its files inline, already decoded from
// base64 by the API. The store keeps them as given in the job's input/ folder.

#include "planner/job/job_spec.hpp"

#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fibrecell::daemon::jobs {

// The job YAML's name inside input/; a submitted file may not use it.
inline constexpr const char* job_yaml_name = "job.yaml";

struct JobInput {
    std::string job_yaml;                                    // the job file's text
    std::vector<std::pair<std::string, std::string>> files;  // relative name -> bytes
    bool start_when_planned = false;                         // `fibrecell submit --start`
    std::string submitted_by;                                // api::CallContext::user
};

// A submission that cannot be stored or planned; the message names the file or key.
class JobInputError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Checks every file name (relative, '/'-separated, no '..', '.', empty part, NUL or backslash,
// not job.yaml, no duplicates) and writes input/ into `dir` (created). Throws JobInputError.
void write_job_input(const std::filesystem::path& dir, const JobInput& input);

// Reads the job YAML of an input/ folder as the planner will, and checks that the files it names
// are among the submitted ones (a remote job may not read the service's own files). Returns the
// job. Throws config::ConfigError naming "job.yaml" and the key.
planner::JobSpec check_job_input(const std::filesystem::path& input_dir, const JobInput& input);

}  // namespace fibrecell::daemon::jobs
