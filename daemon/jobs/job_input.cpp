#include "daemon/jobs/job_input.hpp"

#include "config/durable_file.hpp"

#include <set>

namespace fibrecell::daemon::jobs {
namespace {

namespace fs = std::filesystem;

void check_name(const std::string& name) {
    const std::string where = "files[\"" + name + "\"]: ";
    if (name.empty()) throw JobInputError("files: a file has an empty name");
    if (name.size() > 1024) throw JobInputError(where + "name longer than 1024 characters");
    if (name.find('\0') != std::string::npos || name.find('\\') != std::string::npos)
        throw JobInputError(where + "name must not contain NUL or '\\'");
    if (name.front() == '/') throw JobInputError(where + "must be a relative name");
    std::size_t start = 0;
    while (start <= name.size()) {
        const std::size_t end = std::min(name.find('/', start), name.size());
        const std::string part = name.substr(start, end - start);
        if (part.empty() || part == "." || part == "..")
            throw JobInputError(where + "parts must not be empty, '.' or '..'");
        start = end + 1;
    }
    if (name == job_yaml_name)
        throw JobInputError(where + "the name is taken by the job file itself");
}

// `file` lies inside `dir` (both absolute, normalised).
bool inside(const fs::path& dir, const fs::path& file) {
    const fs::path rel = file.lexically_normal().lexically_relative(dir.lexically_normal());
    return !rel.empty() && *rel.begin() != ".." && rel.is_relative();
}

}  // namespace

void write_job_input(const fs::path& dir, const JobInput& input) {
    std::set<std::string> names;
    for (const auto& [name, bytes] : input.files) {
        check_name(name);
        if (!names.insert(name).second) throw JobInputError("files[\"" + name + "\"]: given twice");
    }
    fs::create_directories(dir);
    config::write_file_durably(dir / job_yaml_name, input.job_yaml);
    for (const auto& [name, bytes] : input.files) {
        const fs::path path = dir / name;
        fs::create_directories(path.parent_path());
        config::write_file_durably(path, bytes);
    }
}

planner::JobSpec check_job_input(const fs::path& input_dir, const JobInput& input) {
    const fs::path dir = fs::absolute(input_dir);
    const planner::JobSpec job = planner::parse_job(input.job_yaml, job_yaml_name, dir.string());
    const auto check = [&](const std::string& path, const char* key) {
        if (!path.empty() && !inside(dir, path))
            throw JobInputError(std::string(job_yaml_name) + ": " + key +
                                ": must name a file submitted with the job, not " + path);
    };
    check(job.model.mesh_path, "model.mesh");
    check(job.model.stress_path, "model.stress");
    return job;
}

}  // namespace fibrecell::daemon::jobs
