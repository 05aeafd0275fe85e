#include "planner/io/vtk_reader.hpp"

#include "planner/input_error.hpp"
#include "planner/io/file_text.hpp"
#include "planner/io/number_parse.hpp"
#include "planner/io/stress_components.hpp"
#include "planner/io/text_scanner.hpp"
#include "planner/io/validate_model.hpp"
#include "planner/io/vtk_cell_types.hpp"
#include "planner/io/vtk_values.hpp"

#include <climits>
#include <cmath>
#include <optional>
#include <vector>

namespace fibrecell::planner {
namespace {

enum class Owner { none, cells, points };

// A cell array with 6 or 9 components: a stress candidate until the end of the file.
struct StressArray {
    std::string name;
    int components = 0;
    std::vector<double> values;  // components per cell, for all cells
    std::size_t line = 0;        // line of the array header
    std::size_t bad_line = 0;    // line of the first non-finite value (header line if binary)
    long long bad_cell = -1;
};

constexpr long long kMaxComponents = 1 << 16;

class VtkParser {
  public:
    VtkParser(std::string_view text, const std::string& file) : s_(text, file) {}

    VolumeModel parse() {
        read_header();
        while (!s_.at_end()) {
            const std::string_view kw = s_.token("a section keyword");
            if (iequals(kw, "POINTS"))
                read_points();
            else if (iequals(kw, "CELLS"))
                read_cells();
            else if (iequals(kw, "CELL_TYPES"))
                read_cell_types();
            else if (iequals(kw, "CELL_DATA"))
                read_data_header(Owner::cells);
            else if (iequals(kw, "POINT_DATA"))
                read_data_header(Owner::points);
            else if (iequals(kw, "FIELD"))
                read_field();
            else if (iequals(kw, "METADATA"))
                skip_metadata();
            else if (!read_attribute(kw))
                s_.fail("unexpected keyword '" + shown(kw) + "'");
        }
        return assemble();
    }

  private:
    void read_header() {
        std::string_view line;
        constexpr std::string_view kMagic = "# vtk DataFile Version";
        if (!s_.next_line(line) || line.size() < kMagic.size() ||
            !iequals(line.substr(0, kMagic.size()), kMagic))
            s_.fail("not a legacy VTK file: the first line must be '# vtk DataFile Version x.x'");
        if (!s_.next_line(line)) s_.fail("unexpected end of file: expected the title line");
        const std::string_view format = s_.token("ASCII or BINARY");
        if (iequals(format, "ASCII"))
            binary_ = false;
        else if (iequals(format, "BINARY"))
            binary_ = true;
        else
            s_.fail("expected ASCII or BINARY, found '" + shown(format) + "'");
        s_.expect("DATASET");
        const std::string_view type = s_.token("a dataset type");
        if (!iequals(type, "UNSTRUCTURED_GRID"))
            s_.fail("dataset type " + shown(type) +
                    " is not supported: a tet mesh must be an UNSTRUCTURED_GRID");
    }

    void read_points() {
        if (points_) s_.fail("second POINTS section");
        const long long n = s_.integer("point count", 0, INT_MAX);
        const VtkScalar type = read_vtk_scalar(s_);
        VtkValueStream in(s_, binary_, 3 * n, type, "POINTS");
        points_.emplace(static_cast<std::size_t>(n));
        for (std::size_t i = 0; i < points_->size(); ++i) {
            Eigen::Vector3d& p = (*points_)[i];
            p.x() = in.any_real();
            p.y() = in.any_real();
            p.z() = in.any_real();
            if (!p.allFinite())
                s_.fail("point id " + std::to_string(i) +
                        " has a coordinate that is not a finite number");
        }
        if (have_cells_) check_point_ids_after_points();
    }

    void read_cells() {
        if (have_cells_) s_.fail("second CELLS section");
        const long long first = s_.integer("cell count", 0, INT_MAX);
        const long long second = s_.integer("cell list size", 0, LLONG_MAX / 8);
        if (iequals(s_.peek(), "OFFSETS"))
            read_cells_offsets(first, second);
        else
            read_cells_classic(first, second);
        have_cells_ = true;
    }

    // "CELLS n size": per cell its point count, then its point ids.
    void read_cells_classic(long long cell_count, long long size) {
        VtkValueStream in(s_, binary_, size, VtkScalar::int32, "CELLS");
        if (cell_count > size)
            s_.fail("CELLS lists " + std::to_string(cell_count) + " cells in only " +
                    std::to_string(size) + " values");
        offsets_.reserve(static_cast<std::size_t>(cell_count) + 1);
        connectivity_.reserve(static_cast<std::size_t>(size - cell_count));
        offsets_.push_back(0);
        long long used = 0;
        for (long long c = 0; c < cell_count; ++c) {
            const long long k = in.integer();
            ++used;
            if (k < 0 || k > size - used)
                s_.fail("cell id " + std::to_string(c) + ": point count " + std::to_string(k) +
                        " does not fit the CELLS size " + std::to_string(size));
            for (long long j = 0; j < k; ++j) connectivity_.push_back(point_id(in.integer(), c));
            used += k;
            offsets_.push_back(static_cast<long long>(connectivity_.size()));
        }
        if (used != size)
            s_.fail("CELLS size is " + std::to_string(size) + " values but the " +
                    std::to_string(cell_count) + " cells use " + std::to_string(used));
    }

    // VTK 5.1: "CELLS offsets connectivity", then OFFSETS and CONNECTIVITY arrays.
    void read_cells_offsets(long long offset_count, long long connectivity_size) {
        s_.expect("OFFSETS");
        VtkValueStream offsets(s_, binary_, offset_count, read_vtk_scalar(s_), "OFFSETS");
        offsets_.reserve(static_cast<std::size_t>(offset_count));
        for (long long i = 0; i < offset_count; ++i) {
            const long long o = offsets.integer();
            const long long previous = offsets_.empty() ? 0 : offsets_.back();
            if ((i == 0 && o != 0) || o < previous || o > connectivity_size)
                s_.fail("OFFSETS value " + std::to_string(i) + " (" + std::to_string(o) +
                        ") must start at 0, never decrease and stay within the " +
                        std::to_string(connectivity_size) + " connectivity entries");
            offsets_.push_back(o);
        }
        if (offsets_.empty()) offsets_.push_back(0);
        if (offsets_.back() != connectivity_size)
            s_.fail("the last OFFSETS value is " + std::to_string(offsets_.back()) +
                    ", CELLS says " + std::to_string(connectivity_size) + " connectivity entries");
        s_.expect("CONNECTIVITY");
        VtkValueStream ids(s_, binary_, connectivity_size, read_vtk_scalar(s_), "CONNECTIVITY");
        connectivity_.reserve(static_cast<std::size_t>(connectivity_size));
        std::size_t cell = 0;
        for (long long i = 0; i < connectivity_size; ++i) {
            while (offsets_[cell + 1] <= i) ++cell;
            connectivity_.push_back(point_id(ids.integer(), static_cast<long long>(cell)));
        }
    }

    int point_id(long long id, long long cell) const {
        const long long limit = points_ ? static_cast<long long>(points_->size()) : INT_MAX;
        if (id < 0 || id >= limit)
            s_.fail("cell id " + std::to_string(cell) + " refers to point id " +
                    std::to_string(id) +
                    (points_ ? ", but POINTS has " + std::to_string(points_->size()) + " points"
                             : ", which is not a valid id"));
        return static_cast<int>(id);
    }

    // POINTS after CELLS is unusual but legal: check the ids once the count is known.
    void check_point_ids_after_points() const {
        for (std::size_t c = 0; c + 1 < offsets_.size(); ++c)
            for (long long i = offsets_[c]; i < offsets_[c + 1]; ++i)
                point_id(connectivity_[static_cast<std::size_t>(i)], static_cast<long long>(c));
    }

    long long cell_count() const { return static_cast<long long>(offsets_.size()) - 1; }

    void read_cell_types() {
        if (!have_cells_) s_.fail("CELL_TYPES before CELLS");
        if (have_types_) s_.fail("second CELL_TYPES section");
        const long long n = s_.integer("cell type count", 0, INT_MAX);
        if (n != cell_count())
            s_.fail("CELL_TYPES has " + std::to_string(n) + " entries but CELLS has " +
                    std::to_string(cell_count()) + " cells");
        VtkValueStream in(s_, binary_, n, VtkScalar::int32, "CELL_TYPES");
        tets_.reserve(static_cast<std::size_t>(n));
        tet_cells_.reserve(static_cast<std::size_t>(n));
        for (long long c = 0; c < n; ++c) {
            const long long type = in.integer();
            const auto cell = static_cast<std::size_t>(c);
            const long long points = offsets_[cell + 1] - offsets_[cell];
            const long long needed = type == kVtkTetra ? 4 : type == kVtkTriangle ? 3 : -1;
            if (needed < 0)
                s_.fail("cell id " + std::to_string(c) + " has type " + std::to_string(type) +
                        " (" + vtk_cell_type_name(type) +
                        "): only tetrahedra (VTK_TETRA, 10) are read; triangles (5) are skipped");
            if (points != needed)
                s_.fail("cell id " + std::to_string(c) + " is a " + vtk_cell_type_name(type) +
                        " with " + std::to_string(points) + " points (needs " +
                        std::to_string(needed) + ")");
            if (type != kVtkTetra) continue;
            const auto* ids = &connectivity_[static_cast<std::size_t>(offsets_[cell])];
            tets_.push_back({static_cast<int>(ids[0]), static_cast<int>(ids[1]),
                             static_cast<int>(ids[2]), static_cast<int>(ids[3])});
            tet_cells_.push_back(c);
        }
        have_types_ = true;
        connectivity_ = {};  // the tets hold what is needed now
    }

    void read_data_header(Owner owner) {
        const char* section = owner == Owner::cells ? "CELL_DATA" : "POINT_DATA";
        const long long n = s_.integer("data count");
        long long expected = 0;
        if (owner == Owner::cells) {
            if (!have_types_) s_.fail("CELL_DATA before CELLS and CELL_TYPES");
            expected = cell_count();
        } else {
            if (!points_) s_.fail("POINT_DATA before POINTS");
            expected = static_cast<long long>(points_->size());
        }
        if (n != expected)
            s_.fail(std::string(section) + " " + std::to_string(n) + " does not match the " +
                    std::to_string(expected) + (owner == Owner::cells ? " cells" : " points"));
        owner_ = owner;
        owner_count_ = n;
    }

    // Dataset attributes: true when `kw` is one (and it has been read or skipped).
    bool read_attribute(std::string_view kw) {
        const bool attribute = iequals(kw, "SCALARS") || iequals(kw, "VECTORS") ||
                               iequals(kw, "NORMALS") || iequals(kw, "TENSORS") ||
                               iequals(kw, "TENSORS6") || iequals(kw, "TEXTURE_COORDINATES") ||
                               iequals(kw, "GLOBAL_IDS") || iequals(kw, "PEDIGREE_IDS") ||
                               iequals(kw, "COLOR_SCALARS") || iequals(kw, "LOOKUP_TABLE");
        if (!attribute) return false;
        if (owner_ == Owner::none)
            s_.fail(std::string(kw) + " outside a CELL_DATA or POINT_DATA section");

        const std::string name(s_.token("an array name"));
        const std::size_t line = s_.line();
        if (iequals(kw, "COLOR_SCALARS")) {
            const long long n = s_.integer("color component count", 1, kMaxComponents);
            skip_vtk_values(s_, binary_, owner_count_ * n,
                            binary_ ? VtkScalar::uint8 : VtkScalar::float32, "COLOR_SCALARS");
            return true;
        }
        if (iequals(kw, "LOOKUP_TABLE")) {
            const long long n = s_.integer("lookup table size", 0, INT_MAX);
            skip_vtk_values(s_, binary_, 4 * n, binary_ ? VtkScalar::uint8 : VtkScalar::float32,
                            "LOOKUP_TABLE");
            return true;
        }
        long long components = 1;
        VtkScalar type = VtkScalar::float32;
        if (iequals(kw, "TEXTURE_COORDINATES")) {
            components = s_.integer("texture dimension", 1, 3);
            type = read_vtk_scalar(s_);
        } else {
            type = read_vtk_scalar(s_);
            if (iequals(kw, "SCALARS")) {
                if (!s_.at_line_end())
                    components = s_.integer("component count", 1, kMaxComponents);
                s_.expect("LOOKUP_TABLE");
                s_.token("a lookup table name");
            } else if (iequals(kw, "VECTORS") || iequals(kw, "NORMALS")) {
                components = 3;
            } else if (iequals(kw, "TENSORS")) {
                components = 9;
            } else if (iequals(kw, "TENSORS6")) {
                components = 6;
            }
        }
        read_array(name, components, owner_count_, type, line);
        return true;
    }

    void read_field() {
        s_.token("a field name");
        const long long arrays = s_.integer("field array count", 0, INT_MAX);
        s_.check_count(arrays, 2, "field array");
        for (long long i = 0; i < arrays; ++i) {
            const std::string name(s_.token("a field array name"));
            if (name == "NULL_ARRAY") continue;
            const std::size_t line = s_.line();
            const long long components = s_.integer("component count", 1, kMaxComponents);
            const long long tuples = s_.integer("tuple count", 0, INT_MAX);
            const VtkScalar type = read_vtk_scalar(s_);
            if (owner_ != Owner::none && tuples != owner_count_)
                s_.fail("FIELD array '" + shown(name) + "' has " + std::to_string(tuples) +
                        " tuples, but the data section has " + std::to_string(owner_count_));
            read_array(name, components, tuples, type, line);
            if (iequals(s_.peek(), "METADATA")) {
                s_.token("METADATA");
                skip_metadata();
            }
        }
    }

    // Keeps 6/9-component cell arrays as stress candidates; skips everything else.
    void read_array(const std::string& name, long long components, long long tuples, VtkScalar type,
                    std::size_t line) {
        const long long count = components * tuples;
        const std::string what = "array '" + shown(name) + "'";
        const bool candidate = owner_ == Owner::cells && is_stress_component_count(components) &&
                               type != VtkScalar::string && type != VtkScalar::bit;
        if (!candidate) {
            skip_vtk_values(s_, binary_, count, type, what);
            return;
        }
        VtkValueStream in(s_, binary_, count, type, what);
        StressArray array{name, static_cast<int>(components), {}, line, 0, -1};
        array.values.resize(static_cast<std::size_t>(count));
        for (long long i = 0; i < count; ++i) {
            const double v = in.any_real();
            // Rejected only if this array turns out to be the stress.
            if (!std::isfinite(v) && array.bad_cell < 0) {
                array.bad_line = s_.line();
                array.bad_cell = i / components;
            }
            array.values[static_cast<std::size_t>(i)] = v;
        }
        stress_arrays_.push_back(std::move(array));
    }

    // METADATA blocks (VTK 9) run to the next empty line.
    void skip_metadata() {
        std::string_view line;
        s_.next_line(line);
        while (s_.next_line(line) && !trim(line).empty()) {
        }
    }

    const StressArray* choose_stress() const {
        const StressArray* named = nullptr;
        for (const StressArray& a : stress_arrays_) {
            if (!iequals(a.name, "stress")) continue;
            if (named)
                throw InputError::at_line(s_.file(), a.line,
                                          "a second cell array named 'stress' (first on line " +
                                              std::to_string(named->line) + ")");
            named = &a;
        }
        if (named) return named;
        if (stress_arrays_.size() <= 1)
            return stress_arrays_.empty() ? nullptr : &stress_arrays_.front();
        std::string names;
        for (const StressArray& a : stress_arrays_)
            names += (names.empty() ? "'" : ", '") + shown(a.name) + "'";
        throw InputError(s_.file(), "",
                         "several 6/9-component cell arrays (" + names +
                             ") and none is named 'stress': name the stress array 'stress'");
    }

    VolumeModel assemble() {
        const std::string& file = s_.file();
        if (!points_) throw InputError(file, "", "no POINTS section");
        if (!have_cells_) throw InputError(file, "", "no CELLS section");
        if (!have_types_) throw InputError(file, "", "no CELL_TYPES section");

        VolumeModel model;
        model.mesh.vertices = std::move(*points_);
        model.mesh.tets = std::move(tets_);
        if (const StressArray* a = choose_stress()) {
            if (a->bad_cell >= 0)
                throw InputError::at_line(file, a->bad_line,
                                          "stress array '" + shown(a->name) +
                                              "' has a value that is not a finite number (cell "
                                              "id " +
                                              std::to_string(a->bad_cell) + ")");
            auto& stress = model.stress.emplace();
            stress.reserve(tet_cells_.size());
            for (const long long cell : tet_cells_)
                stress.push_back(stress_from_components(
                    &a->values[static_cast<std::size_t>(cell * a->components)], a->components));
        }
        FileNumbering numbering{"cell id", "point id", 0, std::move(tet_cells_), {}};
        validate_model(model, file, numbering);
        return model;
    }

    TextScanner s_;
    bool binary_ = false;
    std::optional<std::vector<Eigen::Vector3d>> points_;
    bool have_cells_ = false;
    std::vector<long long> offsets_;       // cell c uses connectivity_[offsets_[c], offsets_[c+1])
    std::vector<long long> connectivity_;  // point ids
    bool have_types_ = false;
    std::vector<Tet> tets_;
    std::vector<long long> tet_cells_;  // VTK cell id of each tet
    Owner owner_ = Owner::none;
    long long owner_count_ = 0;
    std::vector<StressArray> stress_arrays_;
};

}  // namespace

VolumeModel parse_vtk(std::string_view text, const std::string& file) {
    return VtkParser(text, file).parse();
}

VolumeModel read_vtk(const std::string& path) {
    return parse_vtk(read_file_text(path), path);
}

}  // namespace fibrecell::planner
