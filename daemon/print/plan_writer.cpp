#include "daemon/print/plan_writer.hpp"

#include "daemon/print/program_file.hpp"

#include "config/utc_time.hpp"

#include <system_error>

namespace fibrecell::daemon::print {

namespace fs = std::filesystem;

PlanWriter::PlanWriter(fs::path plan_dir) : files_(std::move(plan_dir)) {
    std::error_code ec;
    fs::remove(dir() / manifest_name, ec);
    if (ec) throw std::system_error(ec, "cannot remove " + (dir() / manifest_name).string());
    for (const char* folder : {"rapid", "preview"}) {
        fs::remove_all(dir() / folder, ec);
        if (ec) throw std::system_error(ec, "cannot remove " + (dir() / folder).string());
    }
    config::sync_directory(fs::exists(dir()) ? dir() : dir().parent_path());
}

void PlanWriter::write(const std::string& relative, std::string_view bytes) {
    files_.write(relative, bytes);
    entries_.push_back(manifest_entry(relative, bytes));
}

void PlanWriter::finish(const std::string& job, const nlohmann::json& cell) {
    files_.commit();  // every file's entry on the disk before the manifest names it
    const Manifest m{job, config::utc_now(), cell, entries_};
    config::write_file_durably(dir() / manifest_name, manifest_json_text(m));
}

void write_print_files(PlanWriter& out, const RobotPlan& plan, PrintFile print) {
    print.chunks.clear();
    for (const auto& m : plan.rapid.modules) {
        print.chunks.push_back(chunk_entry(m));
        out.write(print.chunks.back().file, m.text);
    }
    out.write("program.json", program_json_text(plan.program, plan.rapid.joints));
    out.write("print.json", print_json_text(print));
}

}  // namespace fibrecell::daemon::print
