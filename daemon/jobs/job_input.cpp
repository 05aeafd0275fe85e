#include "daemon/jobs/job_input.hpp"

#include "config/durable_file.hpp"

#include <set>

namespace fibrecell::daemon::jobs {
namespace {

namespace fs = std::filesystem;

// A file system's limit for one name (NAME_MAX on Linux).
constexpr std::size_t max_part_bytes = 255;

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
        if (part.size() > max_part_bytes)
            throw JobInputError(where + "a part of the name is longer than " +
                                std::to_string(max_part_bytes) + " bytes");
        start = end + 1;
    }
    if (name == job_yaml_name)
        throw JobInputError(where + "the name is taken by the job file itself");
}

}  // namespace

void write_job_input(const fs::path& dir, const JobInput& input) {
    std::set<std::string> names;
    for (const auto& [name, bytes] : input.files) {
        check_name(name);
        if (!names.insert(name).second) throw JobInputError("files[\"" + name + "\"]: given twice");
    }
    // "a" and "a/b" cannot both be: one would be a file and a folder.
    for (const std::string& name : names)
        for (std::size_t slash = name.find('/'); slash != std::string::npos;
             slash = name.find('/', slash + 1))
            if (names.contains(name.substr(0, slash)))
                throw JobInputError("files[\"" + name + "\"]: lies in \"" + name.substr(0, slash) +
                                    "\", which is a file of the job");
    fs::create_directories(dir);
    config::write_file_durably(dir / job_yaml_name, input.job_yaml);
    for (const auto& [name, bytes] : input.files) {
        const fs::path path = dir / name;
        fs::create_directories(path.parent_path());
        config::write_file_durably(path, bytes);
    }
}

planner::JobSpec check_job_input(const fs::path& input_dir, const JobInput& input) {
    return planner::parse_job(input.job_yaml, job_yaml_name, fs::absolute(input_dir).string(),
                              planner::JobFiles::submitted_only);
}

}  // namespace fibrecell::daemon::jobs
