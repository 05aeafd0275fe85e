#include "planner/io/msh_reader.hpp"

#include "planner/input_error.hpp"
#include "planner/io/file_text.hpp"
#include "planner/io/gmsh_element_types.hpp"
#include "planner/io/number_parse.hpp"
#include "planner/io/stress_components.hpp"
#include "planner/io/text_scanner.hpp"
#include "planner/io/validate_model.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <map>
#include <unordered_map>
#include <utility>
#include <vector>

namespace fibrecell::planner {
namespace {

using DimTag = std::pair<int, long long>;  // (dimension, tag) of a physical group or entity

// An $ElementData view with 6 or 9 components. Sized by its entries, not by the mesh, so that
// many small views cannot make the reader allocate more than the file holds.
struct StressView {
    std::string name;
    int components = 0;
    std::size_t line = 0;        // line of its $ElementData header
    std::vector<int> tets;       // tet of each entry
    std::vector<double> values;  // components per entry
    std::size_t bad_line = 0;    // first non-finite value
};

constexpr long long kMaxTags = 1 << 16;

class MshParser {
  public:
    MshParser(std::string_view text, const std::string& file) : s_(text, file) {}

    VolumeModel parse() {
        read_format();
        while (!s_.at_end()) {
            const std::string_view tok = s_.token("a section");
            if (tok.size() < 2 || tok[0] != '$')
                s_.fail("expected a section header such as $Nodes, found '" + shown(tok) + "'");
            const std::string_view name = tok.substr(1);
            if (name == "PhysicalNames")
                read_physical_names();
            else if (name == "Entities" && version_ == 4)
                read_entities();
            else if (name == "Nodes")
                read_nodes();
            else if (name == "Elements")
                read_elements();
            else if (name == "ElementData")
                read_element_data();
            else if (name == "MeshFormat")
                s_.fail("second $MeshFormat section");
            else if (name.starts_with("End"))
                s_.fail("'" + shown(tok) + "' without its section");
            else
                skip_section(name);
        }
        return assemble();
    }

  private:
    void read_format() {
        s_.expect("$MeshFormat");
        const std::string_view version = s_.token("the MSH version");
        const auto v = parse_real(version);
        if (v && *v >= 2 && *v < 3)
            version_ = 2;
        else if (version == "4.1")
            version_ = 4;
        else if (v && *v >= 4 && *v < 4.1)
            s_.fail("MSH 4.0 is not supported: save the mesh as MSH 4.1 or 2.2");
        else
            s_.fail("MSH version '" + shown(version) + "' is not supported (2.2 or 4.1)");
        const long long file_type = s_.integer("the file type (0 = ASCII)");
        if (file_type == 1)
            s_.fail("binary MSH files are not supported: save as ASCII (Gmsh: Mesh.Binary = 0)");
        if (file_type != 0) s_.fail("unknown MSH file type " + std::to_string(file_type));
        s_.integer("the data size");
        expect_end("MeshFormat");
    }

    void read_physical_names() {
        const long long n = s_.integer("the number of physical names", 0, INT_MAX);
        s_.check_count(n, 8, "physical name");
        for (long long i = 0; i < n; ++i) {
            const int dim = static_cast<int>(s_.integer("a physical dimension", 0, 3));
            const long long tag = s_.integer("a physical tag");
            physical_names_[{dim, tag}] = std::string(s_.quoted("a physical name"));
        }
        expect_end("PhysicalNames");
    }

    // MSH 4.1: which physical groups each geometric entity belongs to.
    void read_entities() {
        std::array<long long, 4> counts{};
        for (long long& c : counts) {
            c = s_.integer("an entity count", 0, INT_MAX);
            s_.check_count(c, 8, "entity");
        }
        for (int dim = 0; dim < 4; ++dim) {
            for (long long i = 0; i < counts[static_cast<std::size_t>(dim)]; ++i) {
                const long long tag = s_.integer("an entity tag");
                const int coordinates = dim == 0 ? 3 : 6;  // a point, or a bounding box
                for (int k = 0; k < coordinates; ++k) s_.real("an entity coordinate");
                const long long n = s_.integer("the number of physical tags", 0, kMaxTags);
                std::vector<long long>& physicals = entity_physicals_[{dim, tag}];
                for (long long k = 0; k < n; ++k) physicals.push_back(s_.integer("a physical tag"));
                if (dim > 0) {
                    const long long b = s_.integer("the number of bounding entities", 0, INT_MAX);
                    s_.check_count(b, 2, "bounding entity");
                    for (long long k = 0; k < b; ++k) s_.integer("a bounding entity tag");
                }
            }
        }
        expect_end("Entities");
    }

    // MSH 4's head of $Nodes and $Elements: the number of blocks and of items, the smallest and
    // largest tag; both counts checked against what is left of the file (`item_bytes` at least
    // an item).
    struct BlocksHeader {
        long long blocks, items;
    };
    BlocksHeader read_blocks_header(const std::string& item, std::size_t item_bytes) {
        const long long blocks = s_.integer("the number of " + item + " blocks", 0, INT_MAX);
        const long long items = s_.integer("the number of " + item + "s", 0, INT_MAX);
        s_.integer("the minimum " + item + " tag");
        s_.integer("the maximum " + item + " tag");
        s_.check_count(blocks, 8, item + " block");
        s_.check_count(items, item_bytes, item);
        return {blocks, items};
    }

    void read_nodes() {
        if (have_nodes_) s_.fail("second $Nodes section");
        if (version_ == 2) {
            const long long n = s_.integer("the number of nodes", 0, INT_MAX);
            s_.check_count(n, 8, "node");
            reserve_nodes(n);
            for (long long i = 0; i < n; ++i) {
                const long long tag = s_.integer("a node tag");
                add_node(tag, read_point());
            }
        } else {
            const auto [blocks, n] = read_blocks_header("node", 8);
            reserve_nodes(n);
            std::vector<long long> tags;
            for (long long b = 0; b < blocks; ++b) {
                const long long dim = s_.integer("an entity dimension", 0, 3);
                s_.integer("an entity tag");
                const long long parametric = s_.integer("the parametric flag", 0, 1);
                const long long in_block =
                    s_.integer("the number of nodes in the block", 0,
                               n - static_cast<long long>(node_tags_.size()));
                tags.clear();
                for (long long i = 0; i < in_block; ++i) tags.push_back(s_.integer("a node tag"));
                for (long long i = 0; i < in_block; ++i) {
                    add_node(tags[static_cast<std::size_t>(i)], read_point());
                    if (parametric) s_.skip_tokens(dim, "a parametric coordinate");
                }
            }
            if (static_cast<long long>(node_tags_.size()) != n)
                s_.fail("$Nodes announces " + std::to_string(n) + " nodes but its blocks hold " +
                        std::to_string(node_tags_.size()));
        }
        expect_end("Nodes", " (wrong node count?)");
        have_nodes_ = true;
    }

    Eigen::Vector3d read_point() {
        const double x = s_.real("a node coordinate");
        const double y = s_.real("a node coordinate");
        const double z = s_.real("a node coordinate");
        return {x, y, z};
    }

    void reserve_nodes(long long n) {
        node_xyz_.reserve(static_cast<std::size_t>(n));
        node_tags_.reserve(static_cast<std::size_t>(n));
        node_index_.reserve(static_cast<std::size_t>(n));
    }

    void add_node(long long tag, const Eigen::Vector3d& x) {
        const auto [it, inserted] = node_index_.emplace(tag, static_cast<int>(node_tags_.size()));
        if (!inserted) s_.fail("node tag " + std::to_string(tag) + " appears twice");
        node_tags_.push_back(tag);
        node_xyz_.push_back(x);
    }

    void read_elements() {
        if (!have_nodes_) s_.fail("$Elements before $Nodes");
        if (have_elements_) s_.fail("second $Elements section");
        std::vector<long long> physicals;
        if (version_ == 2) {
            const long long n = s_.integer("the number of elements", 0, INT_MAX);
            s_.check_count(n, 8, "element");
            element_index_.reserve(static_cast<std::size_t>(n));
            for (long long i = 0; i < n; ++i) {
                const long long tag = s_.integer("an element tag");
                const GmshElementType type = element_type(s_.integer("an element type"));
                const long long tag_count = s_.integer("the number of element tags", 0, kMaxTags);
                physicals.clear();
                for (long long k = 0; k < tag_count; ++k) {
                    const long long t = s_.integer("an element tag");
                    // The first tag is the physical group; 0 means none.
                    if (k == 0 && t != 0) physicals.push_back(t);
                }
                read_element(tag, type, physicals);
            }
        } else {
            const auto [blocks, n] = read_blocks_header("element", 4);
            element_index_.reserve(static_cast<std::size_t>(n));
            long long seen = 0;
            for (long long b = 0; b < blocks; ++b) {
                const int dim = static_cast<int>(s_.integer("an entity dimension", 0, 3));
                const long long entity = s_.integer("an entity tag");
                const GmshElementType type = element_type(s_.integer("an element type"));
                const long long in_block =
                    s_.integer("the number of elements in the block", 0, n - seen);
                const auto it = entity_physicals_.find({dim, entity});
                physicals = it == entity_physicals_.end() ? std::vector<long long>{} : it->second;
                for (long long i = 0; i < in_block; ++i)
                    read_element(s_.integer("an element tag"), type, physicals);
                seen += in_block;
            }
            if (seen != n)
                s_.fail("$Elements announces " + std::to_string(n) +
                        " elements but its blocks hold " + std::to_string(seen));
        }
        expect_end("Elements", " (wrong element count?)");
        have_elements_ = true;
    }

    GmshElementType element_type(long long id) const {
        const auto type = gmsh_element_type(id);
        if (!type) s_.fail("unknown Gmsh element type " + std::to_string(id));
        if (type->id == kGmshTetrahedron10)
            s_.fail(
                "second-order tetrahedra (Gmsh type 11) are not supported: mesh with "
                "first-order tets (Mesh.ElementOrder = 1)");
        if (type->dimension == 3 && type->id != kGmshTetrahedron)
            s_.fail(std::string(type->name) + " elements (Gmsh type " + std::to_string(id) +
                    ") are not supported: only 4-node tetrahedra");
        return *type;
    }

    // The node tags of one element, after its tag (and, in MSH 2, its type and tags).
    void read_element(long long tag, const GmshElementType& type,
                      const std::vector<long long>& physicals) {
        std::array<int, 4> nodes{};
        for (int k = 0; k < type.nodes; ++k) {
            const long long node = s_.integer("a node tag");
            const auto it = node_index_.find(node);
            if (it == node_index_.end())
                s_.fail("element tag " + std::to_string(tag) + " refers to node tag " +
                        std::to_string(node) + ", which is not in $Nodes");
            if (k < 4) nodes[static_cast<std::size_t>(k)] = it->second;
        }
        const bool tet = type.id == kGmshTetrahedron;
        const auto [it, inserted] =
            element_index_.emplace(tag, tet ? static_cast<int>(tets_.size()) : -1);
        if (!inserted) s_.fail("element tag " + std::to_string(tag) + " appears twice");
        if (tet) {
            tets_.push_back(nodes);
            tet_tags_.push_back(tag);
        }
        if (!tet && type.id != kGmshTriangle) return;
        for (const long long physical : physicals) {
            std::vector<int>& group = group_nodes_[{type.dimension, physical}];
            group.insert(group.end(), nodes.begin(), nodes.begin() + type.nodes);
        }
    }

    void read_element_data() {
        if (!have_elements_) s_.fail("$ElementData before $Elements");
        const std::size_t header_line = s_.line();
        const long long strings = s_.integer("the number of string tags", 0, kMaxTags);
        std::string name;
        for (long long i = 0; i < strings; ++i) {
            const std::string_view tag = s_.quoted("a string tag");
            if (i == 0) name = tag;
        }
        const long long reals = s_.integer("the number of real tags", 0, kMaxTags);
        for (long long i = 0; i < reals; ++i) s_.real("a real tag");
        const long long integers = s_.integer("the number of integer tags", 3, kMaxTags);
        s_.integer("the time step");
        const long long components = s_.integer("the number of components", 1, kMaxTags);
        const long long entries = s_.integer("the number of elements with data", 0, INT_MAX);
        for (long long i = 3; i < integers; ++i) s_.integer("an integer tag");
        s_.check_count(entries, 2 * static_cast<std::size_t>(components + 1), "element data");

        const bool candidate = is_stress_component_count(components);
        StressView view{name, static_cast<int>(components), header_line, {}, {}, 0};
        seen_in_view_.resize(tets_.size(), -1);
        const int view_number = static_cast<int>(views_.size());
        for (long long i = 0; i < entries; ++i) {
            const long long tag = s_.integer("an element tag");
            const auto it = element_index_.find(tag);
            if (it == element_index_.end())
                s_.fail("$ElementData refers to element tag " + std::to_string(tag) +
                        ", which is not in $Elements");
            if (!candidate || it->second < 0) {
                s_.skip_tokens(components, "an element value");
                continue;
            }
            int& seen = seen_in_view_[static_cast<std::size_t>(it->second)];
            if (seen == view_number)
                s_.fail("element tag " + std::to_string(tag) + " appears twice in this view");
            seen = view_number;
            view.tets.push_back(it->second);
            for (long long k = 0; k < components; ++k) {
                const double v = s_.any_real("a stress component");
                // Rejected only if this view turns out to be the stress.
                if (!std::isfinite(v) && view.bad_line == 0) view.bad_line = s_.line();
                view.values.push_back(v);
            }
        }
        expect_end("ElementData", " (wrong number of elements or components?)");
        if (candidate) views_.push_back(std::move(view));
    }

    void skip_section(std::string_view name) {
        const std::string end = "$End" + std::string(name);
        const std::size_t start = s_.line();
        while (!s_.at_end())
            if (s_.token(end) == end) return;
        throw InputError::at_line(s_.file(), start,
                                  "section $" + shown(name) + " is not closed by " + shown(end));
    }

    void expect_end(std::string_view section, std::string_view hint = "") {
        const std::string end = "$End" + std::string(section);
        const std::string_view tok = s_.token(end);
        if (tok != end)
            s_.fail("expected " + end + ", found '" + shown(tok) + "'" + std::string(hint));
    }

    const StressView* choose_stress() const {
        const StressView* named = nullptr;
        for (const StressView& v : views_) {
            if (!iequals(v.name, "stress")) continue;
            if (named)
                throw InputError::at_line(s_.file(), v.line,
                                          "a second $ElementData view named 'stress' (first on "
                                          "line " +
                                              std::to_string(named->line) +
                                              "): keep one time step");
            named = &v;
        }
        if (named) return named;
        if (views_.size() <= 1) return views_.empty() ? nullptr : &views_.front();
        std::string names;
        for (const StressView& v : views_)
            names += (names.empty() ? "'" : ", '") + shown(v.name) + "'";
        throw InputError(s_.file(), "",
                         "several 6/9-component $ElementData views (" + names +
                             ") and none is named 'stress': name the stress view 'stress'");
    }

    VolumeModel assemble() {
        const std::string& file = s_.file();
        if (!have_nodes_) throw InputError(file, "", "no $Nodes section");
        if (!have_elements_) throw InputError(file, "", "no $Elements section");

        // Keep the nodes the tets use, in file order.
        std::vector<int> new_index(node_tags_.size(), -1);
        for (const auto& t : tets_)
            for (const int n : t) new_index[static_cast<std::size_t>(n)] = 0;
        VolumeModel model;
        FileNumbering numbering{"element tag", "node tag", 1, std::move(tet_tags_), {}};
        for (std::size_t n = 0; n < node_tags_.size(); ++n) {
            if (new_index[n] < 0) continue;
            new_index[n] = static_cast<int>(model.mesh.vertices.size());
            model.mesh.vertices.push_back(node_xyz_[n]);
            numbering.vertex_numbers.push_back(node_tags_[n]);
        }
        model.mesh.tets.reserve(tets_.size());
        for (const auto& t : tets_)
            model.mesh.tets.push_back({new_index[static_cast<std::size_t>(t[0])],
                                       new_index[static_cast<std::size_t>(t[1])],
                                       new_index[static_cast<std::size_t>(t[2])],
                                       new_index[static_cast<std::size_t>(t[3])]});

        for (const auto& [dim_tag, nodes] : group_nodes_) {
            const auto named = physical_names_.find(dim_tag);
            const std::string name = named != physical_names_.end()
                                         ? named->second
                                         : "physical_" + std::to_string(dim_tag.second);
            std::vector<int>& group = model.vertex_groups[name];
            for (const int n : nodes)
                if (new_index[static_cast<std::size_t>(n)] >= 0)
                    group.push_back(new_index[static_cast<std::size_t>(n)]);
        }

        if (const StressView* view = choose_stress()) {
            if (view->bad_line != 0)
                throw InputError::at_line(file, view->bad_line,
                                          "stress view '" + shown(view->name) +
                                              "' has a value that is not a finite number");
            std::vector<StressTensor> stress(tets_.size());
            std::vector<char> given(tets_.size(), 0);
            for (std::size_t e = 0; e < view->tets.size(); ++e) {
                const auto t = static_cast<std::size_t>(view->tets[e]);
                stress[t] = stress_from_components(
                    &view->values[e * static_cast<std::size_t>(view->components)],
                    view->components);
                given[t] = 1;
            }
            const auto missing = std::find(given.begin(), given.end(), 0);
            if (missing != given.end())
                throw InputError(
                    file, numbering.element_name(static_cast<std::size_t>(missing - given.begin())),
                    "no value in $ElementData view '" + shown(view->name) + "' (line " +
                        std::to_string(view->line) + ")");
            model.stress = std::move(stress);
        }
        validate_model(model, file, numbering);
        return model;
    }

    TextScanner s_;
    int version_ = 2;
    std::map<DimTag, std::string> physical_names_;
    std::map<DimTag, std::vector<long long>> entity_physicals_;
    bool have_nodes_ = false;
    std::vector<Eigen::Vector3d> node_xyz_;
    std::vector<long long> node_tags_;
    std::unordered_map<long long, int> node_index_;  // node tag -> position in node_xyz_
    bool have_elements_ = false;
    std::vector<std::array<int, 4>> tets_;  // positions in node_xyz_
    std::vector<long long> tet_tags_;
    std::unordered_map<long long, int> element_index_;  // element tag -> tet, or -1 for others
    std::map<DimTag, std::vector<int>> group_nodes_;    // physical group -> node positions
    std::vector<StressView> views_;
    std::vector<int> seen_in_view_;  // per tet: the last candidate view that gave it a value
};

}  // namespace

VolumeModel parse_msh(std::string_view text, const std::string& file) {
    return MshParser(text, file).parse();
}

VolumeModel read_msh(const std::string& path) {
    return parse_msh(read_file_text(path), path);
}

}  // namespace fibrecell::planner
