#pragma once
// A print job as the planner sees it: the typed form of the job YAML (docs/job-format.md).
// Defaults are the paper's (Table 2 and Section 4); units are in the names.

#include "planner/field/incompatibility.hpp"
#include "planner/mesh/region.hpp"

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace fibrecell::planner {

struct LoadSpec {
    std::string region;       // name of a region in JobSpec::regions
    Eigen::Vector3d force_n;  // total force on the region [N], in the model frame
};

// A load case for the built-in FEA, used when the model carries no stress.
struct LoadCaseSpec {
    double youngs_modulus_mpa = 3500.0;  // PLA
    double poisson_ratio = 0.36;
    std::vector<std::string> supports;  // regions fixed in all three directions
    std::vector<LoadSpec> loads;
};

struct ModelSpec {
    std::string mesh_path;                  // absolute, resolved against the job file's folder
    std::string stress_path;                // optional per-element stress text file ("" = none)
    std::optional<LoadCaseSpec> load_case;  // optional; exclusive with stress_path
};

// Where the part sits on the bed: rotated about x, then y, then z, then moved so that its lowest
// point is on the bed (z = 0) and its bounding-box centre is at position_mm.
struct PlacementSpec {
    Eigen::Vector3d rotate_deg = Eigen::Vector3d::Zero();
    Eigen::Vector2d position_mm = Eigen::Vector2d(150.0, 150.0);
};

struct LayerScheduleSpec {
    double pla_layer_height_mm = 0.8;
    double ccf_layer_height_mm = 0.05;
    // Which PLA layers (1-based) get a CCF layer on top. Empty with ccf_on_all = false: none.
    bool ccf_on_all = true;
    std::vector<int> ccf_after_pla;  // explicit list, when not all
    int ccf_every = 0;               // > 0: every n-th PLA layer starting at ccf_first
    int ccf_first = 1;

    bool has_ccf_after(int pla_layer) const;  // pla_layer is 1-based
};

// field: the paper's isocurves of one scalar field; contour_zigzag: the load-blind baseline;
// field_dense: stripes along the stress at the fibre spacing (planner/fibre/stripe_pattern.hpp).
enum class Strategy { field, contour_zigzag, field_dense };
std::string_view to_string(Strategy s);
// The strategy of a job file's or the CLI's name; throws std::invalid_argument for another.
Strategy strategy_named(std::string_view name);

// How much fibre a CCF layer gets (planner.fibre_budget): what the strategy lays by itself
// (none), what the contour-zigzag baseline lays on the same layer (baseline: the paper's
// comparison, same fibre in a different place), or a length per layer.
struct FibreBudget {
    enum class Kind { none, baseline, metres_per_layer };
    Kind kind = Kind::none;
    double metres_per_layer = 0;  // for metres_per_layer
};

// The range a planner setting is read with: [min, max], or (min, max] when min_exclusive. Shared
// by the job file and `fibrecell plan --sweep`, so both refuse the same values.
struct SettingRange {
    double min, max;
    bool min_exclusive = false;
};
inline constexpr SettingRange p_range{0, 10};
inline constexpr SettingRange sigma_cap_percentile_range{0, 100, true};
inline constexpr SettingRange crowded_fraction_range{0, 0.5};

struct PlannerSpec {
    Strategy strategy = Strategy::field;
    double mu = 3.0;   // rule-2 threshold |sigma_1 / sigma_2| < mu
    double eta = 0.5;  // incompatibility threshold (Eq. 2)
    IncompatibilityRule incompatibility_rule = IncompatibilityRule::all_neighbours;
    // The field processing of Section 4.1, each step switchable for the paper's ablation (its
    // Fig. 10: without them the toolpaths turn and oscillate).
    bool mst_reorientation = true;
    bool incompatibility_removal = true;
    double p = 1.0;  // density exponent of u_f = sigma^p v/|v| (Eq. 5)
    // sigma_f is capped at this percentile of its layer before Eq. 5 (100: the paper, no cap), so
    // that one stress singularity does not set the spacing of the whole layer. 90 lays more fibre
    // than 99 with a better density correlation on every bundled and reference part
    // (docs/job-format.md, "Stress singularities").
    double sigma_cap_percentile = 90.0;
    // The fraction of a piece's area where isocurves may crowd closer than W when n is chosen
    // (0: the paper, the single closest pair decides); there they are cut back to W.
    double crowded_fraction = 0.05;
    double fibre_spacing_mm = 1.0;  // W: minimal spacing between fibre paths
    FibreBudget fibre_budget;
    int smoothing_iterations = 50;  // local Laplacian smoothing per layer
    // Cutter to nozzle tip as the job states it, if it does. It is the cell's hardware: the print
    // uses the cell's value and refuses a job that states another (daemon/print/print_settings).
    std::optional<double> cutter_distance_mm;
};

struct HeadProcessSpec {
    double speed_mm_s;         // printing speed
    double travel_speed_mm_s;  // lift, travel and head turns with this nozzle
    double nozzle_temp_c;      // M104/M109 for the print
    double line_width_mm;      // deposited line (PLA: the flow) or ribbon (CCF) width
    // The nozzle the job was made for, if it says: the cell's mounted nozzle must be this one.
    std::optional<double> nozzle_diameter_mm;
};

struct ProcessSpec {
    HeadProcessSpec pla{12.0, 100.0, 200.0, 0.8, std::nullopt};
    HeadProcessSpec ccf{5.0, 100.0, 250.0, 1.2, std::nullopt};
};

// The predicted stiffness of the printed part (job `analysis`, docs/mechanics.md): the load case
// solved again with the fibres in it. Defaults are published data (docs/mechanics.md).
struct AnalysisSpec {
    bool enabled = true;                  // runs whenever a load case is known
    double fibre_modulus_mpa = 230000.0;  // E_f along the fibre (T300-class carbon)
    double fibre_volume_fraction = 0.25;  // of the CCF ribbon's section
    // For a model that came with its stress file, the load case to predict under; a model with
    // model.load_case is analysed under that one.
    std::optional<LoadCaseSpec> load_case;
};

struct JobSpec {
    std::string name;
    std::string job_file;  // where it was read from (for messages)
    ModelSpec model;
    std::vector<Region> regions;
    PlacementSpec placement;
    LayerScheduleSpec layers;
    PlannerSpec planner;
    std::vector<std::string> boundary_fibre_regions;
    ProcessSpec process;
    AnalysisSpec analysis;

    // The load case the analysis uses: the model's, else analysis.load_case, else none.
    const LoadCaseSpec* analysis_load_case() const;
    const Region* find_region(const std::string& name) const;
};

// Reads and validates a job file; relative paths resolve against its folder. Throws
// config::ConfigError naming the file, line and key path on any problem.
JobSpec load_job_file(const std::string& path);

// Where a job's files may be: a job file on disk names any file; a submitted job only the files
// it came with (in base_dir).
enum class JobFiles { anywhere, submitted_only };

// The job's files moved from folder `from` to folder `to` (the service's store renames a submitted
// job's folder once it has an id): its file paths are made to point into `to`.
void move_job_files(JobSpec& job, const std::string& from, const std::string& to);

// The same from text (jobs submitted over the socket carry their YAML inline).
JobSpec parse_job(const std::string& yaml_text, const std::string& origin,
                  const std::string& base_dir, JobFiles files);

}  // namespace fibrecell::planner
