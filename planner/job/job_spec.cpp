#include "planner/job/job_spec.hpp"

#include "config/yaml_section.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace fibrecell::planner {
namespace fs = std::filesystem;
using config::Section;

namespace {

constexpr double kBig = 1e9;  // an upper bound for values with no natural limit

Eigen::Vector3d to_vector(const std::array<double, 3>& a) {
    return {a[0], a[1], a[2]};
}

// `file` lies inside `dir` (both absolute), by name: the job's own files are never links.
bool lies_inside(const fs::path& dir, const fs::path& file) {
    const fs::path rel = file.lexically_normal().lexically_relative(dir.lexically_normal());
    return !rel.empty() && *rel.begin() != ".." && rel.is_relative();
}

std::string resolve_file(Section& s, std::string_view key, const std::string& base_dir,
                         JobFiles files) {
    const std::string raw = s.get<std::string>(key);
    fs::path p(raw);
    if (p.is_relative()) p = fs::path(base_dir) / p;
    // The error_code form: a name the file system cannot hold (too long) is just not a file.
    std::error_code ec;
    if (files == JobFiles::submitted_only) {
        // One answer for a file outside the job and a missing one, so the host's files cannot be
        // probed through it.
        if (!lies_inside(fs::absolute(base_dir), fs::absolute(p)) || !fs::is_regular_file(p, ec))
            s.fail(key, "must name a file submitted with the job, not " + raw);
    } else if (!fs::is_regular_file(p, ec)) {
        s.fail(key, "file not found: " + p.string());
    }
    return p.lexically_normal().string();
}

Region read_region(const std::string& name, Section s) {
    Region r{name, GroupRegion{}};
    const int kinds = s.has("box") + s.has("cylinder") + s.has("group");
    if (kinds != 1) s.fail_here("must have exactly one of box, cylinder, group");
    if (s.has("box")) {
        Section b = s.section("box");
        BoxRegion box{to_vector(b.vec3("min")), to_vector(b.vec3("max"))};
        if ((box.min.array() > box.max.array()).any()) b.fail("max", "must not be below min");
        b.finish();
        r.shape = box;
    } else if (s.has("cylinder")) {
        Section c = s.section("cylinder");
        CylinderRegion cyl;
        cyl.point = to_vector(c.vec3("point"));
        cyl.axis = to_vector(c.vec3_or("axis", {0, 0, 1}));
        if (cyl.axis.norm() < 1e-12) c.fail("axis", "must not be the zero vector");
        cyl.axis.normalize();
        cyl.radius_mm = c.number("radius_mm", 0, 0, kBig, true);
        cyl.tolerance_mm = c.number("tolerance_mm", 0.1, 0, kBig);
        cyl.facing = to_vector(c.vec3_or("facing", {0, 0, 0}));
        if (cyl.facing.norm() > 0) cyl.facing.normalize();
        c.finish();
        r.shape = cyl;
    } else {
        r.shape = GroupRegion{s.get<std::string>("group")};
    }
    s.finish();
    return r;
}

LoadCaseSpec read_load_case(Section s) {
    LoadCaseSpec lc;
    Section m = s.section("material");
    lc.youngs_modulus_mpa = m.number("youngs_modulus_mpa", lc.youngs_modulus_mpa, 0, kBig, true);
    lc.poisson_ratio = m.number("poisson_ratio", lc.poisson_ratio, -0.99, 0.49);
    m.finish();
    lc.supports = s.get<std::vector<std::string>>("supports");
    if (lc.supports.empty())
        s.fail("supports", "needs at least one region (the part must be held)");
    for (Section l : s.sections("loads")) {
        LoadSpec load{l.get<std::string>("region"), to_vector(l.vec3("force_n"))};
        l.finish();
        lc.loads.push_back(load);
    }
    if (lc.loads.empty()) s.fail("loads", "needs at least one load");
    s.finish();
    return lc;
}

LayerScheduleSpec read_layers(Section s) {
    LayerScheduleSpec l;
    l.pla_layer_height_mm = s.number("pla_layer_height_mm", l.pla_layer_height_mm, 0.01, 5, false);
    l.ccf_layer_height_mm = s.number("ccf_layer_height_mm", l.ccf_layer_height_mm, 0.001, 1);
    const YAML::Node n = s.node("ccf_after_pla");
    if (!n || n.IsNull()) {
        // absent: the default, a CCF layer on every PLA layer
    } else if (n.IsScalar()) {
        const std::string word = n.Scalar();
        if (word != "all" && word != "none")
            s.fail("ccf_after_pla",
                   "must be all, none, a list of PLA layer numbers, or "
                   "{every: N, first: K}; got '" +
                       word + "'");
        l.ccf_on_all = word == "all";
    } else if (n.IsSequence()) {
        l.ccf_on_all = false;
        l.ccf_after_pla = s.get<std::vector<int>>("ccf_after_pla");
        for (int i : l.ccf_after_pla)
            if (i < 1)
                s.fail("ccf_after_pla", "PLA layer numbers start at 1, got " + std::to_string(i));
        std::sort(l.ccf_after_pla.begin(), l.ccf_after_pla.end());
    } else {
        Section e = s.section("ccf_after_pla");
        l.ccf_on_all = false;
        l.ccf_every = e.integer("every", 1, 1, 100000);
        l.ccf_first = e.integer("first", 1, 1, 100000);
        e.finish();
    }
    s.finish();
    return l;
}

// `none`, `baseline` or a positive number of metres per CCF layer.
FibreBudget read_fibre_budget(Section& s) {
    FibreBudget b;
    if (!s.has("fibre_budget")) return b;
    const YAML::Node n = s.node("fibre_budget");
    const std::string text = n.IsScalar() ? n.as<std::string>() : "";
    if (text == "none") return b;
    if (text == "baseline") {
        b.kind = FibreBudget::Kind::baseline;
        return b;
    }
    char* end = nullptr;
    const double metres = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !(metres > 0) ||
        !std::isfinite(metres))
        s.fail("fibre_budget",
               "must be none, baseline or a positive length in metres per CCF layer, not '" + text +
                   "'");
    b.kind = FibreBudget::Kind::metres_per_layer;
    b.metres_per_layer = metres;
    return b;
}

PlannerSpec read_planner(Section s) {
    PlannerSpec p;
    p.strategy = strategy_named(s.choice("strategy", "field", {"field", "contour-zigzag", "field-dense"}));
    p.mu = s.number("mu", p.mu, 0, kBig, true);
    p.eta = s.number("eta", p.eta, -1, 1);
    const std::string rule = s.choice("incompatibility_rule", "all", {"all", "majority", "any"});
    p.incompatibility_rule = rule == "all"        ? IncompatibilityRule::all_neighbours
                             : rule == "majority" ? IncompatibilityRule::majority
                                                  : IncompatibilityRule::any_neighbour;
    p.mst_reorientation = s.get_or("mst_reorientation", p.mst_reorientation);
    p.incompatibility_removal = s.get_or("incompatibility_removal", p.incompatibility_removal);
    p.p = s.number("p", p.p, p_range.min, p_range.max);
    p.sigma_cap_percentile =
        s.number("sigma_cap_percentile", p.sigma_cap_percentile, sigma_cap_percentile_range.min,
                 sigma_cap_percentile_range.max, sigma_cap_percentile_range.min_exclusive);
    p.crowded_fraction = s.number("crowded_fraction", p.crowded_fraction,
                                  crowded_fraction_range.min, crowded_fraction_range.max);
    p.fibre_budget = read_fibre_budget(s);
    p.fibre_spacing_mm = s.number("fibre_spacing_mm", p.fibre_spacing_mm, 0.1, 100);
    p.smoothing_iterations = s.integer("smoothing_iterations", p.smoothing_iterations, 0, 10000);
    if (s.has("cutter_distance_mm"))
        p.cutter_distance_mm = s.number("cutter_distance_mm", 0, 0, 10000);
    s.finish();
    return p;
}

HeadProcessSpec read_head(Section s, HeadProcessSpec h) {
    h.speed_mm_s = s.number("speed_mm_s", h.speed_mm_s, 0, 1000, true);
    h.travel_speed_mm_s = s.number("travel_speed_mm_s", h.travel_speed_mm_s, 0, 1000, true);
    h.nozzle_temp_c = s.number("nozzle_temp_c", h.nozzle_temp_c, 0, 400);
    h.line_width_mm = s.number("line_width_mm", h.line_width_mm, 0.05, 20, false);
    if (s.has("nozzle_diameter_mm"))
        h.nozzle_diameter_mm = s.number("nozzle_diameter_mm", 0, 0.05, 5);
    s.finish();
    return h;
}

void check_region_names(Section& s, std::string_view key, const std::vector<std::string>& names,
                        const JobSpec& job) {
    for (const auto& n : names)
        if (!job.find_region(n))
            s.fail(key, "names region '" + n + "', which `regions` does not define");
}

// A load case whose supports and loads name regions the job defines.
LoadCaseSpec read_job_load_case(Section lc, const JobSpec& job) {
    LoadCaseSpec spec = read_load_case(lc);
    check_region_names(lc, "supports", spec.supports, job);
    for (const auto& load : spec.loads)
        if (!job.find_region(load.region))
            lc.fail("loads", "names region '" + load.region + "', which `regions` does not define");
    return spec;
}

AnalysisSpec read_analysis(Section s, const JobSpec& job) {
    AnalysisSpec a;
    a.enabled = s.get_or("enabled", a.enabled);
    a.fibre_modulus_mpa = s.number("fibre_modulus_mpa", a.fibre_modulus_mpa, 0, 2e6, true);
    a.fibre_volume_fraction =
        s.number("fibre_volume_fraction", a.fibre_volume_fraction, 0, 1, true);
    if (s.has("load_case")) {
        if (job.model.load_case)
            s.fail("load_case",
                   "the model has its own load_case, which the analysis uses; give one here only "
                   "for a model that comes with a stress file");
        a.load_case = read_job_load_case(s.section("load_case"), job);
    }
    const LoadCaseSpec* lc = job.model.load_case ? &*job.model.load_case
                             : a.load_case       ? &*a.load_case
                                                 : nullptr;
    if (lc && a.fibre_modulus_mpa <= lc->youngs_modulus_mpa)
        s.fail("fibre_modulus_mpa", "must exceed the matrix's Young's modulus (" +
                                        std::to_string(lc->youngs_modulus_mpa) + " MPa)");
    s.finish();
    return a;
}

}  // namespace

bool LayerScheduleSpec::has_ccf_after(int pla_layer) const {
    if (ccf_on_all) return true;
    if (ccf_every > 0) return pla_layer >= ccf_first && (pla_layer - ccf_first) % ccf_every == 0;
    return std::binary_search(ccf_after_pla.begin(), ccf_after_pla.end(), pla_layer);
}

std::string_view to_string(Strategy s) {
    switch (s) {
        case Strategy::field: return "field";
        case Strategy::contour_zigzag: return "contour-zigzag";
        case Strategy::field_dense: return "field-dense";
    }
    return "field";
}

Strategy strategy_named(std::string_view name) {
    if (name == "contour-zigzag") return Strategy::contour_zigzag;
    if (name == "field-dense") return Strategy::field_dense;
    if (name == "field") return Strategy::field;
    throw std::invalid_argument("no strategy '" + std::string(name) +
                                "' (field, contour-zigzag or field-dense)");
}

const LoadCaseSpec* JobSpec::analysis_load_case() const {
    if (model.load_case) return &*model.load_case;
    if (analysis.load_case) return &*analysis.load_case;
    return nullptr;
}

const Region* JobSpec::find_region(const std::string& region_name) const {
    for (const auto& r : regions)
        if (r.name == region_name) return &r;
    return nullptr;
}

JobSpec parse_job(const std::string& yaml_text, const std::string& origin,
                  const std::string& base_dir, JobFiles files) {
    Section root = Section::load_text(yaml_text, origin);
    if (root.is_null()) root.fail_here("is empty");
    JobSpec job;
    job.job_file = origin;
    job.name = root.get<std::string>("name");
    if (job.name.empty()) root.fail("name", "must not be empty");

    Section regions = root.section("regions");
    for (const std::string& name : regions.keys())
        job.regions.push_back(read_region(name, regions.section(name)));
    regions.finish();

    Section model = root.section("model");
    if (model.is_null()) root.fail("model", "is required");
    job.model.mesh_path = resolve_file(model, "mesh", base_dir, files);
    if (model.has("stress")) job.model.stress_path = resolve_file(model, "stress", base_dir, files);
    if (model.has("load_case")) {
        if (!job.model.stress_path.empty())
            model.fail("load_case", "give either a stress file or a load case, not both");
        job.model.load_case = read_job_load_case(model.section("load_case"), job);
    }
    model.finish();

    Section placement = root.section("placement");
    job.placement.rotate_deg = to_vector(placement.vec3_or("rotate_deg", {0, 0, 0}));
    const auto pos = placement.get_or<std::vector<double>>("position_mm", {150.0, 150.0});
    if (pos.size() != 2) placement.fail("position_mm", "must be a list of 2 numbers [x, y]");
    job.placement.position_mm = {pos[0], pos[1]};
    placement.finish();

    job.layers = read_layers(root.section("layers"));
    job.planner = read_planner(root.section("planner"));

    job.boundary_fibre_regions = root.get_or<std::vector<std::string>>("boundary_fibres", {});
    check_region_names(root, "boundary_fibres", job.boundary_fibre_regions, job);

    Section process = root.section("process");
    job.process.pla = read_head(process.section("pla"), job.process.pla);
    job.process.ccf = read_head(process.section("ccf"), job.process.ccf);
    process.finish();

    job.analysis = read_analysis(root.section("analysis"), job);

    root.finish();
    return job;
}

void move_job_files(JobSpec& job, const std::string& from, const std::string& to) {
    const auto moved = [&](std::string& path) {
        if (path.empty()) return;
        path = (fs::path(to) / fs::path(path).lexically_relative(from)).string();
    };
    moved(job.model.mesh_path);
    moved(job.model.stress_path);
}

JobSpec load_job_file(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw config::ConfigError(path + ": cannot open job file");
    std::stringstream text;
    text << in.rdbuf();
    const fs::path dir = fs::absolute(fs::path(path)).parent_path();
    return parse_job(text.str(), path, dir.string(), JobFiles::anywhere);
}

}  // namespace fibrecell::planner
