#pragma once
// Writes a plan directory so that it is complete or recognisably not: every file durable (temp,
// rename, file and folder fsync through config::DurableFiles) and its size and sha256 noted, then,
// last, manifest.json. A plan cut short by a crash has no manifest and is never printed; the
// service marks a job planned only after finish() returned.
//
//   PlanWriter out(plan_dir);
//   out.write("toolpaths.json", text);
//   write_print_files(out, robot_plan, print_file);
//   out.finish(job.name, cell_facts(cell));

#include "config/durable_file.hpp"
#include "daemon/print/manifest.hpp"
#include "daemon/print/print_file.hpp"
#include "daemon/print/robot_plan.hpp"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::daemon::print {

class PlanWriter {
  public:
    // Removes what an earlier plan in `dir` had that this one replaces: manifest.json first (so
    // that a plan cut short has none), then rapid/ and preview/.
    explicit PlanWriter(std::filesystem::path plan_dir);

    // `relative`: '/'-separated, inside the plan directory. Throws std::system_error.
    void write(const std::string& relative, std::string_view bytes);
    // Every file on the disk, then manifest.json (planned now, for `cell`). Throws
    // std::system_error.
    void finish(const std::string& job, const nlohmann::json& cell);

    const std::filesystem::path& dir() const { return files_.root(); }

  private:
    config::DurableFiles files_;
    std::vector<ManifestEntry> entries_;
};

// The print's files: rapid/FcChunkNNNN.mod, program.json and print.json (with its chunk table
// filled in from the plan's modules).
void write_print_files(PlanWriter& out, const RobotPlan& plan, PrintFile print);

}  // namespace fibrecell::daemon::print
