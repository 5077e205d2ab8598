// Gmsh MSH: write 4.1 ASCII; read 4.1 ASCII, 4.1 binary and 2.2 ASCII.
//
// Hexahedra are element type 5, whose node order is VTK's (Gmsh 4.8's
// getElementProperties(5) lists the reference nodes (-1,-1,-1) (1,-1,-1) (1,1,-1)
// (-1,1,-1) and then the same four at z = +1). Gmsh entity tags are positive, so
// sub-volume s is written as volume entity (and physical group "SV<s>") s + 1, and a
// volume entity tag t reads back as sub-volume t - 1. Node tags are 1-based.
#include <algorithm>
#include <charconv>
#include <cstring>
#include <limits>
#include <map>
#include <unordered_map>

#include "io/detail/io_common.h"
#include "io/mesh_io.h"

namespace vorohex::io {

namespace {

// Gmsh's 20-node hexahedron (type 17) lists mid-edge nodes on edges 0-1 0-3 0-4 1-2 1-5
// 2-3 2-6 3-7 4-5 4-7 5-6 6-7 (Gmsh manual, "Node ordering"); entry k is the VTK mid-edge
// index (core::kHexEdges) of Gmsh's node 8 + k.
constexpr int kGmshMidToVtk[12] = {0, 3, 8, 1, 9, 2, 10, 11, 4, 7, 5, 6};

void append_box(std::string* t, const core::BoundingBox& box) {
  for (const core::Vec3* p : {&box.min, &box.max})
    for (int k = 0; k < 3; ++k) {
      *t += ' ';
      detail::append_double(t, (*p)[k]);
    }
}

}  // namespace

bool write_msh(const core::HexMesh& mesh, const std::string& path, const WriteOptions& options,
               std::string* error) {
  if (!detail::check_hex_indices(mesh, error)) return false;
  const auto& sub = mesh.sub_volumes();
  for (std::int32_t s : sub)
    if (s < 0 || s == std::numeric_limits<std::int32_t>::max()) {
      detail::set_error(error,
                        "MSH output needs sub-volume ids >= 0 (found " + std::to_string(s) + ")");
      return false;
    }
  const bool quadratic = mesh.order() == 2;
  const auto& mid = mesh.mid_edge_nodes();
  // Members and bounding box of each sub-volume; a mesh without hexahedra keeps one
  // volume entity so that its nodes have an entity to belong to.
  struct Volume {
    std::vector<std::size_t> hexes;
    core::BoundingBox box;
  };
  std::map<std::int32_t, Volume> volumes;
  const auto& hexes = mesh.hexes();
  const auto& points = mesh.points();
  for (std::size_t h = 0; h < hexes.size(); ++h) {
    Volume& v = volumes[sub[h]];
    if (v.hexes.empty()) v.box.min = v.box.max = points[hexes[h][0]];
    v.hexes.push_back(h);
    for (std::int32_t n : hexes[h]) {
      v.box.min = v.box.min.cwiseMin(points[n]);
      v.box.max = v.box.max.cwiseMax(points[n]);
    }
  }
  if (volumes.empty()) volumes[0].box = mesh.bounding_box();

  // Named groups become Gmsh entities of their own dimension and tag (Face7 = surface 7,
  // physical group 7 "Face7") holding their elements: points, lines, quads (3-node lines
  // and 8-node quads for a second-order mesh).
  struct Entity {
    const NamedGroup* group;
    core::BoundingBox box;
    std::size_t elements;
  };
  std::vector<Entity> entities[3];
  for (const NamedGroup& g : options.groups) {
    const std::size_t n = g.dim == 2 ? g.faces.size() : g.dim == 1 ? g.edges.size() : 1;
    if (g.nodes.empty() || n == 0 || g.dim < 0 || g.dim > 2) continue;
    if (g.dim == 0 && mesh.node_class(core::NodeId(g.nodes[0])).dim != 0) continue;
    Entity e{&g, {}, n};
    e.box.min = e.box.max = points[g.nodes[0]];
    for (std::int32_t v : g.nodes) {
      e.box.min = e.box.min.cwiseMin(points[v]);
      e.box.max = e.box.max.cwiseMax(points[v]);
    }
    entities[g.dim].push_back(e);
  }

  detail::OutputFile out;
  if (!out.open(path, error)) return false;
  std::string& t = out.text();
  t += "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n";
  detail::append_int(&t, static_cast<std::int64_t>(volumes.size() + entities[0].size() +
                                                   entities[1].size() + entities[2].size()));
  t += '\n';
  for (int dim = 0; dim < 3; ++dim)
    for (const Entity& e : entities[dim])
      t += std::to_string(dim) + " " + std::to_string(e.group->id) + " \"" + e.group->name + "\"\n";
  for (const auto& [s, v] : volumes) {
    t += "3 ";
    detail::append_int(&t, s + 1);
    t += " \"SV" + std::to_string(s) + "\"\n";
  }
  t += "$EndPhysicalNames\n$Entities\n";
  t += std::to_string(entities[0].size()) + " " + std::to_string(entities[1].size()) + " " +
       std::to_string(entities[2].size()) + " ";
  detail::append_int(&t, static_cast<std::int64_t>(volumes.size()));
  t += '\n';
  for (const Entity& e : entities[0]) {
    detail::append_int(&t, e.group->id);
    for (int k = 0; k < 3; ++k) {
      t += ' ';
      detail::append_double(&t, points[e.group->nodes[0]][k]);
    }
    t += " 1 " + std::to_string(e.group->id) + "\n";
  }
  for (int dim = 1; dim < 3; ++dim)
    for (const Entity& e : entities[dim]) {
      detail::append_int(&t, e.group->id);
      append_box(&t, e.box);
      t += " 1 " + std::to_string(e.group->id) + " 0\n";
    }
  for (const auto& [s, v] : volumes) {
    detail::append_int(&t, s + 1);
    append_box(&t, v.box);
    t += " 1 ";
    detail::append_int(&t, s + 1);
    t += " 0\n";
  }
  t += "$EndEntities\n$Nodes\n";
  const auto nn = static_cast<std::int64_t>(points.size());
  if (nn == 0) {
    t += "0 0 0 0\n";
  } else {
    // All nodes in one block of the first volume; elements may use nodes of any entity.
    t += "1 " + std::to_string(nn) + " 1 " + std::to_string(nn) + "\n3 " +
         std::to_string(volumes.begin()->first + 1) + " 0 " + std::to_string(nn) + "\n";
    for (std::int64_t i = 1; i <= nn; ++i) {
      detail::append_int(&t, i);
      t += '\n';
      out.flush_if_full();
    }
    for (const core::Vec3& p : points) {
      detail::append_double(&t, p.x());
      t += ' ';
      detail::append_double(&t, p.y());
      t += ' ';
      detail::append_double(&t, p.z());
      t += '\n';
      out.flush_if_full();
    }
  }
  t += "$EndNodes\n$Elements\n";
  const auto nh = static_cast<std::int64_t>(hexes.size());
  std::size_t blocks = volumes.size(), total = hexes.size();
  for (int dim = 0; dim < 3; ++dim)
    for (const Entity& e : entities[dim]) ++blocks, total += e.elements;
  if (total == 0) {
    t += "0 0 0 0\n";
  } else {
    // Hexahedra keep tags 1..nh (their index + 1); group elements follow.
    t +=
        std::to_string(blocks) + " " + std::to_string(total) + " 1 " + std::to_string(total) + "\n";
    auto node = [&](std::int32_t n) {
      t += ' ';
      detail::append_int(&t, static_cast<std::int64_t>(n) + 1);
    };
    for (const auto& [s, v] : volumes) {
      t += "3 " + std::to_string(s + 1) + (quadratic ? " 17 " : " 5 ") +
           std::to_string(v.hexes.size()) + "\n";
      for (std::size_t h : v.hexes) {
        detail::append_int(&t, static_cast<std::int64_t>(h) + 1);
        for (std::int32_t n : hexes[h]) node(n);
        if (quadratic)
          for (int k : kGmshMidToVtk) node(mid[h][k]);
        t += '\n';
        out.flush_if_full();
      }
    }
    std::int64_t tag = nh;
    const char* types[3] = {" 15 ", quadratic ? " 8 " : " 1 ", quadratic ? " 16 " : " 3 "};
    for (int dim = 0; dim < 3; ++dim)
      for (const Entity& e : entities[dim]) {
        const NamedGroup& g = *e.group;
        t += std::to_string(dim) + " " + std::to_string(g.id) + types[dim] +
             std::to_string(e.elements) + "\n";
        if (dim == 0) {
          detail::append_int(&t, ++tag);
          node(g.nodes[0]);
          t += '\n';
        }
        for (const GroupEdge& ge : g.edges) {
          detail::append_int(&t, ++tag);
          node(hexes[ge.hex][core::kHexEdges[ge.edge][0]]);
          node(hexes[ge.hex][core::kHexEdges[ge.edge][1]]);
          if (quadratic) node(mid[ge.hex][ge.edge]);
          t += '\n';
        }
        for (const GroupFace& gf : g.faces) {
          detail::append_int(&t, ++tag);
          const auto& quad = core::kHexFaces[gf.face];
          for (int i = 0; i < 4; ++i) node(hexes[gf.hex][quad[i]]);
          if (quadratic)
            for (int i = 0; i < 4; ++i) {
              const int a = quad[i], b = quad[(i + 1) % 4];
              for (int k = 0; k < 12; ++k) {
                const auto& ed = core::kHexEdges[k];
                if ((ed[0] == a && ed[1] == b) || (ed[0] == b && ed[1] == a)) node(mid[gf.hex][k]);
              }
            }
          t += '\n';
          out.flush_if_full();
        }
      }
  }
  t += "$EndElements\n";
  return out.close(error);
}

namespace {

// Gmsh element types: dimension and node count (from Gmsh 4.8's getElementProperties).
struct ElementKind {
  int dim = -1;
  int nodes = 0;
};
ElementKind element_kind(int type) {
  static const std::map<int, ElementKind> kKinds = {
      {1, {1, 2}},    {2, {2, 3}},    {3, {2, 4}},    {4, {3, 4}},    {5, {3, 8}},
      {6, {3, 6}},    {7, {3, 5}},    {8, {1, 3}},    {9, {2, 6}},    {10, {2, 9}},
      {11, {3, 10}},  {12, {3, 27}},  {13, {3, 18}},  {14, {3, 14}},  {15, {0, 1}},
      {16, {2, 8}},   {17, {3, 20}},  {18, {3, 15}},  {19, {3, 13}},  {20, {2, 9}},
      {21, {2, 10}},  {22, {2, 12}},  {23, {2, 15}},  {24, {2, 15}},  {25, {2, 21}},
      {26, {1, 4}},   {27, {1, 5}},   {28, {1, 6}},   {29, {3, 20}},  {30, {3, 35}},
      {31, {3, 56}},  {32, {3, 22}},  {33, {3, 28}},  {36, {2, 16}},  {37, {2, 25}},
      {38, {2, 36}},  {39, {2, 12}},  {40, {2, 16}},  {41, {2, 20}},  {42, {2, 28}},
      {43, {2, 36}},  {44, {2, 45}},  {45, {2, 55}},  {46, {2, 66}},  {47, {2, 49}},
      {48, {2, 64}},  {49, {2, 81}},  {50, {2, 100}}, {51, {2, 121}}, {62, {1, 7}},
      {63, {1, 8}},   {64, {1, 9}},   {65, {1, 10}},  {66, {1, 11}},  {71, {3, 84}},
      {72, {3, 120}}, {73, {3, 165}}, {74, {3, 220}}, {75, {3, 286}}, {92, {3, 64}},
      {93, {3, 125}}, {94, {3, 216}}, {95, {3, 343}}, {96, {3, 512}}, {97, {3, 729}},
      {98, {3, 1000}}};
  const auto it = kKinds.find(type);
  return it == kKinds.end() ? ElementKind{} : it->second;
}

constexpr int kGmshHexahedron = 5;
constexpr int kGmshHexahedron20 = 17;

// Bounds-checked reading of text tokens, lines and little-endian binary values.
class Cursor {
 public:
  explicit Cursor(std::string_view s) : s_(s) {}

  std::size_t pos() const { return pos_; }
  std::size_t remaining() const { return s_.size() - pos_; }
  void skip_space() {
    while (pos_ < s_.size() && is_space(s_[pos_])) ++pos_;
  }
  bool token(std::string_view* t) {
    skip_space();
    const std::size_t b = pos_;
    while (pos_ < s_.size() && !is_space(s_[pos_])) ++pos_;
    *t = s_.substr(b, pos_ - b);
    return pos_ > b;
  }
  template <class T>
  bool number(T* v) {
    std::string_view t;
    if (!token(&t)) return false;
    const char* b = t.data();
    if (!t.empty() && t[0] == '+') ++b;
    const auto r = std::from_chars(b, t.data() + t.size(), *v);
    return r.ec == std::errc() && r.ptr == t.data() + t.size();
  }
  // The rest of the current line (without its newline), which is skipped.
  std::string_view rest_of_line() {
    const std::size_t b = pos_;
    while (pos_ < s_.size() && s_[pos_] != '\n') ++pos_;
    std::string_view t = s_.substr(b, pos_ - b);
    if (pos_ < s_.size()) ++pos_;
    return t;
  }
  // Skips the rest of the current line, newline included.
  void skip_line() {
    while (pos_ < s_.size() && s_[pos_] != '\n') ++pos_;
    if (pos_ < s_.size()) ++pos_;
  }
  bool binary(void* out, std::size_t n) {
    if (remaining() < n) return false;
    std::memcpy(out, s_.data() + pos_, n);  // MSH binary is little-endian, like the host
    pos_ += n;
    return true;
  }
  // Moves past the next occurrence of `marker` (returns false if there is none).
  bool skip_past(std::string_view marker) {
    const std::size_t p = s_.find(marker, pos_);
    if (p == std::string_view::npos) return false;
    pos_ = p + marker.size();
    return true;
  }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }
  std::string_view s_;
  std::size_t pos_ = 0;
};

class MshReader {
 public:
  MshReader(std::string_view data, ReadMeshResult* result) : in_(data), result_(result) {}

  bool read() {
    std::string_view t;
    if (!in_.token(&t) || t != "$MeshFormat")
      return fail("the file does not start with $MeshFormat");
    std::string_view version;
    int file_type = -1;
    if (!in_.token(&version) || !in_.number(&file_type) || !in_.number(&data_size_))
      return fail("invalid $MeshFormat line");
    binary_ = file_type == 1;
    if (file_type != 0 && file_type != 1) return fail("invalid file type in $MeshFormat");
    if (version == "4.1") {
      v4_ = true;
      if (data_size_ != 4 && data_size_ != 8) return fail("unsupported data size");
    } else if (version == "2.2" || version == "2.1" || version == "2") {
      if (binary_) return fail("binary MSH 2 files are not supported (save as MSH 4.1)");
    } else {
      return fail("unsupported MSH version " + std::string(version) + " (use 4.1 or 2.2)");
    }
    if (binary_) {
      in_.skip_line();
      std::int32_t one = 0;
      if (!in_.binary(&one, sizeof one)) return fail("truncated $MeshFormat");
      if (one != 1) return fail("big-endian binary MSH files are not supported");
    }
    if (!in_.skip_past("$EndMeshFormat")) return fail("no $EndMeshFormat");
    while (true) {
      if (!in_.token(&t)) break;
      if (t.empty() || t[0] != '$')
        return fail("unexpected text '" + std::string(t.substr(0, 20)) + "'");
      const std::string section(t.substr(1));
      if (binary_) in_.skip_line();  // binary data starts on the next line
      bool ok = true;
      if (section == "Nodes")
        ok = v4_ ? nodes41() : nodes22();
      else if (section == "Elements")
        ok = v4_ ? elements41() : elements22();
      else if (section == "Entities" && v4_)
        ok = entities41();
      else if (section == "PhysicalNames")
        ok = physical_names();
      else if (!in_.skip_past("$End" + section))
        return fail("section $" + section + " has no end (truncated?)");
      if (!ok) return false;
      if ((section == "Nodes" || section == "Elements" || section == "PhysicalNames" ||
           (section == "Entities" && v4_)) &&
          (!in_.token(&t) || t != "$End" + section))
        return fail("section $" + section + " does not end with $End" + section +
                    " (truncated or inconsistent counts)");
    }
    if (!have_nodes_) return fail("no $Nodes section");
    if (hexes_.empty()) return fail("the file contains no hexahedron (type 5 or 17)");
    const auto quadratic =
        std::count_if(hexes_.begin(), hexes_.end(), [](const Hex& h) { return h.quadratic; });
    if (quadratic > 0 && quadratic < static_cast<std::ptrdiff_t>(hexes_.size()))
      return fail("the file mixes 8-node and 20-node hexahedra");
    store_hexes();
    classify_nodes();
    report_skipped();
    return true;
  }

 private:
  bool fail(const std::string& what) {
    result_->diagnostics.push_back(core::make_error("unreadable_mesh", "MSH: " + what));
    return false;
  }

  bool size_value(std::uint64_t* v) {
    if (!binary_) return in_.number(v);
    if (data_size_ == 8) return in_.binary(v, 8);
    std::uint32_t x = 0;
    if (!in_.binary(&x, 4)) return false;
    *v = x;
    return true;
  }
  bool int_value(std::int32_t* v) { return binary_ ? in_.binary(v, 4) : in_.number(v); }
  bool double_value(double* v) { return binary_ ? in_.binary(v, 8) : in_.number(v); }

  // Rejects counts that the rest of the file cannot hold (at least `bytes` each).
  bool plausible(std::uint64_t count, std::size_t bytes, const char* what) {
    if (count > in_.remaining() / bytes ||
        count > std::uint64_t(std::numeric_limits<std::int32_t>::max()))
      return fail(std::string("the file is too short for ") + std::to_string(count) + " " + what +
                  " (truncated?)");
    return true;
  }

  bool add_node(std::uint64_t tag, const core::Vec3& p) {
    if (tag == 0) return fail("node tag 0 is invalid");
    const auto index = static_cast<std::int32_t>(result_->mesh.num_nodes());
    if (!node_index_.emplace(tag, index).second)
      return fail("node tag " + std::to_string(tag) + " appears twice");
    result_->mesh.add_node(p);
    return true;
  }

  bool node_of(std::uint64_t tag, std::int32_t* index) {
    const auto it = node_index_.find(tag);
    if (it == node_index_.end())
      return fail("an element refers to node " + std::to_string(tag) + ", which does not exist");
    *index = it->second;
    return true;
  }

  // `physical`: MSH 2's physical tag of the element (MSH 4 finds it through the entity).
  bool add_element(std::uint64_t tag, int type, std::int64_t entity,
                   const std::vector<std::uint64_t>& nodes, std::int64_t physical = 0) {
    if (type != kGmshHexahedron && type != kGmshHexahedron20) {
      const int dim = element_kind(type).dim;
      ++skipped_[dim < 3 ? 0 : 1];
      if (dim >= 0 && dim < 3) return classify_element(dim, entity, physical, nodes);
      return true;
    }
    if (entity <= std::numeric_limits<std::int32_t>::min() ||
        entity > std::numeric_limits<std::int32_t>::max())
      return fail("entity tag out of range");
    Hex hex{tag, {}, static_cast<std::int32_t>(entity - 1), {}, type == kGmshHexahedron20};
    for (int k = 0; k < 8; ++k)
      if (!node_of(nodes[k], &hex.nodes[k])) return false;
    if (hex.quadratic)
      for (int k = 0; k < 12; ++k)
        if (!node_of(nodes[8 + k], &hex.mid[kGmshMidToVtk[k]])) return false;
    hexes_.push_back(hex);
    return true;
  }

  // Hexahedra in element-tag order (files group them by entity), so that a written mesh
  // reads back in its own order.
  void store_hexes() {
    std::stable_sort(hexes_.begin(), hexes_.end(),
                     [](const Hex& a, const Hex& b) { return a.tag < b.tag; });
    result_->mesh.reserve(0, hexes_.size());
    std::vector<core::MidEdgeNodes> mid;
    for (const Hex& h : hexes_) {
      result_->mesh.add_hex(h.nodes, h.sub_volume);
      if (h.quadratic) mid.push_back(h.mid);
    }
    if (mid.size() == hexes_.size()) result_->mesh.set_mid_edge_nodes(std::move(mid));
  }

  void report_skipped() {
    if (skipped_[0] > 0 && node_class_.empty())
      result_->diagnostics.push_back(core::make_info(
          "boundary_elements_skipped",
          "Skipped " + std::to_string(skipped_[0]) + " point, line and surface elements"));
    else if (skipped_[0] > 0)
      result_->diagnostics.push_back(core::make_info(
          "boundary_elements_read",
          "Read " + std::to_string(skipped_[0]) + " point, line and surface elements: their " +
              "groups named after the model's entities put " + std::to_string(node_class_.size()) +
              " nodes on their vertex, edge or face"));
    if (skipped_[1] > 0)
      result_->diagnostics.push_back(
          core::make_warning("non_hex_elements_skipped",
                             "Skipped " + std::to_string(skipped_[1]) +
                                 " volume elements that are not hexahedra (8 or 20 nodes)"));
  }

  bool nodes41() {
    std::uint64_t blocks = 0, count = 0, min_tag = 0, max_tag = 0;
    if (!size_value(&blocks) || !size_value(&count) || !size_value(&min_tag) ||
        !size_value(&max_tag))
      return fail("invalid $Nodes header");
    if (!plausible(count, binary_ ? 32 : 8, "nodes") ||
        !plausible(blocks, binary_ ? 20 : 8, "node blocks"))
      return false;
    // Reserve only what the remaining bytes can hold: counts may lie.
    const std::size_t reserve = std::min<std::size_t>(count, in_.remaining() / 32);
    result_->mesh.reserve(reserve, 0);
    node_index_.reserve(reserve);
    std::uint64_t total = 0;
    std::vector<std::uint64_t> tags;
    for (std::uint64_t b = 0; b < blocks; ++b) {
      std::int32_t dim = 0, entity = 0, parametric = 0;
      std::uint64_t n = 0;
      if (!int_value(&dim) || !int_value(&entity) || !int_value(&parametric) || !size_value(&n))
        return fail("invalid node block header");
      if (dim < 0 || dim > 3 || (parametric != 0 && parametric != 1))
        return fail("invalid node block header");
      // Compared as count - total: total + n wraps around for a huge n (found by fuzzing).
      if (n > count - total) return fail("node blocks hold more nodes than announced");
      total += n;
      tags.resize(static_cast<std::size_t>(n));
      for (auto& tag : tags)
        if (!size_value(&tag)) return fail("truncated node tags");
      const int extra = parametric ? dim : 0;
      for (std::uint64_t tag : tags) {
        double x[6];
        for (int k = 0; k < 3 + extra; ++k)
          if (!double_value(&x[k])) return fail("truncated or invalid node coordinates");
        if (!add_node(tag, core::Vec3(x[0], x[1], x[2]))) return false;
      }
    }
    if (total != count) return fail("node blocks hold fewer nodes than announced");
    have_nodes_ = true;
    return true;
  }

  bool elements41() {
    if (!have_nodes_) return fail("$Elements comes before $Nodes");
    std::uint64_t blocks = 0, count = 0, min_tag = 0, max_tag = 0;
    if (!size_value(&blocks) || !size_value(&count) || !size_value(&min_tag) ||
        !size_value(&max_tag))
      return fail("invalid $Elements header");
    if (!plausible(count, binary_ ? 16 : 4, "elements") ||
        !plausible(blocks, binary_ ? 20 : 8, "element blocks"))
      return false;
    hexes_.reserve(std::min<std::size_t>(count, in_.remaining() / 32));
    std::uint64_t total = 0;
    std::vector<std::uint64_t> nodes;
    for (std::uint64_t b = 0; b < blocks; ++b) {
      std::int32_t dim = 0, entity = 0, type = 0;
      std::uint64_t n = 0;
      if (!int_value(&dim) || !int_value(&entity) || !int_value(&type) || !size_value(&n))
        return fail("invalid element block header");
      if (n > count - total) return fail("element blocks hold more elements than announced");
      total += n;
      const ElementKind kind = element_kind(type);
      if (kind.nodes == 0) {
        if (binary_) return fail("unknown element type " + std::to_string(type));
        // ASCII: one element per line, so unknown types can still be skipped.
        in_.skip_line();
        for (std::uint64_t e = 0; e < n; ++e) in_.skip_line();
        skipped_[dim < 3 ? 0 : 1] += n;
        continue;
      }
      nodes.resize(static_cast<std::size_t>(kind.nodes));
      for (std::uint64_t e = 0; e < n; ++e) {
        std::uint64_t tag = 0;
        if (!size_value(&tag)) return fail("truncated element data");
        for (auto& v : nodes)
          if (!size_value(&v)) return fail("truncated element data");
        if (!add_element(tag, type, entity, nodes)) return false;
      }
    }
    if (total != count) return fail("element blocks hold fewer elements than announced");
    return true;
  }

  // $Entities (text or binary): the physical groups of each point, curve and surface, by
  // which the boundary elements name the model entity their nodes lie on.
  bool entities41() {
    std::uint64_t counts[4];
    for (auto& c : counts)
      if (!size_value(&c)) return fail("truncated $Entities");
    for (int dim = 0; dim < 4; ++dim) {
      if (!plausible(counts[dim], 12, "entities")) return false;
      for (std::uint64_t e = 0; e < counts[dim]; ++e) {
        std::int32_t entity = 0, tag = 0;
        double box[6];
        std::uint64_t n = 0;
        if (!int_value(&entity)) return fail("truncated $Entities");
        for (int k = 0; k < (dim == 0 ? 3 : 6); ++k)
          if (!double_value(&box[k])) return fail("truncated $Entities");
        for (int list = 0; list < (dim == 0 ? 1 : 2); ++list) {  // physicals, then boundary
          if (!size_value(&n) || !plausible(n, binary_ ? 4 : 2, "entity tags"))
            return fail("truncated $Entities");
          for (std::uint64_t i = 0; i < n; ++i) {
            if (!int_value(&tag)) return fail("truncated $Entities");
            if (list == 0 && dim < 3) entity_physicals_[{dim, entity}].push_back(tag);
          }
        }
      }
    }
    return true;
  }

  // $PhysicalNames (text in both versions): `dim tag "name"` per line.
  bool physical_names() {
    std::uint64_t count = 0;
    if (!in_.number(&count) || !plausible(count, 6, "physical names"))
      return fail("invalid $PhysicalNames");
    in_.skip_line();
    for (std::uint64_t i = 0; i < count; ++i) {
      std::int32_t dim = 0, tag = 0;
      if (!in_.number(&dim) || !in_.number(&tag)) return fail("invalid $PhysicalNames line");
      std::string_view name = in_.rest_of_line();
      while (!name.empty() && (name.front() == ' ' || name.front() == '"')) name.remove_prefix(1);
      while (!name.empty() && (name.back() == '\r' || name.back() == ' ' || name.back() == '"'))
        name.remove_suffix(1);
      // A group named as VoroHex names the model's entities ("Vertex1", "Edge3", "Face7":
      // FreeCAD's names, as written by write_msh) stands for that entity; others for none.
      static const char* const kPrefix[3] = {"Vertex", "Edge", "Face"};
      if (dim < 0 || dim > 2) continue;
      const std::string_view prefix = kPrefix[dim];
      if (name.size() <= prefix.size() || name.substr(0, prefix.size()) != prefix) continue;
      std::int32_t id = 0;
      const auto r = std::from_chars(name.data() + prefix.size(), name.data() + name.size(), id);
      if (r.ec == std::errc() && r.ptr == name.data() + name.size() && id > 0)
        physical_entity_[{dim, tag}] = core::NodeClass{std::int8_t(dim), id};
    }
    return true;
  }

  // A point, line or surface element in a physical group that stands for a model entity
  // puts its nodes on that entity; a node in several keeps the lowest dimension (a node on
  // an edge is also in the quads of both its faces).
  bool classify_element(int dim, std::int64_t entity, std::int64_t physical,
                        const std::vector<std::uint64_t>& nodes) {
    std::vector<std::int32_t> own;  // MSH 2: the element's physical tag
    const std::vector<std::int32_t>* physicals = &own;
    if (v4_) {
      const auto it = entity_physicals_.find({dim, static_cast<std::int32_t>(entity)});
      if (it != entity_physicals_.end()) physicals = &it->second;
    } else if (physical > 0 && physical <= std::numeric_limits<std::int32_t>::max()) {
      own.push_back(static_cast<std::int32_t>(physical));
    }
    for (std::int32_t ph : *physicals) {
      const auto named = physical_entity_.find({dim, ph});
      if (named == physical_entity_.end()) continue;
      const core::NodeClass c = named->second;
      for (std::uint64_t tag : nodes) {
        std::int32_t index = 0;
        if (!node_of(tag, &index)) return false;
        auto [it, fresh] = node_class_.try_emplace(index, c);
        if (!fresh && c.dim < it->second.dim) it->second = c;
      }
    }
    return true;
  }

  void classify_nodes() {
    for (const auto& [node, c] : node_class_) result_->mesh.set_node_class(core::NodeId(node), c);
  }

  bool nodes22() {
    std::uint64_t count = 0;
    if (!in_.number(&count)) return fail("invalid $Nodes header");
    if (!plausible(count, 8, "nodes")) return false;
    // Reserve only what the remaining bytes can hold: counts may lie.
    const std::size_t reserve = std::min<std::size_t>(count, in_.remaining() / 32);
    result_->mesh.reserve(reserve, 0);
    node_index_.reserve(reserve);
    for (std::uint64_t i = 0; i < count; ++i) {
      std::uint64_t tag = 0;
      double x[3];
      if (!in_.number(&tag) || !in_.number(&x[0]) || !in_.number(&x[1]) || !in_.number(&x[2]))
        return fail("truncated or invalid node line");
      if (!add_node(tag, core::Vec3(x[0], x[1], x[2]))) return false;
    }
    have_nodes_ = true;
    return true;
  }

  bool elements22() {
    if (!have_nodes_) return fail("$Elements comes before $Nodes");
    std::uint64_t count = 0;
    if (!in_.number(&count)) return fail("invalid $Elements header");
    if (!plausible(count, 8, "elements")) return false;
    std::vector<std::uint64_t> nodes(8);
    for (std::uint64_t i = 0; i < count; ++i) {
      std::uint64_t tag = 0;
      std::int32_t type = 0, ntags = 0;
      if (!in_.number(&tag) || !in_.number(&type) || !in_.number(&ntags) || ntags < 0 || ntags > 64)
        return fail("truncated or invalid element line");
      std::int64_t entity = 1, physical = 0;
      for (std::int32_t k = 0; k < ntags; ++k) {
        std::int64_t v = 0;
        if (!in_.number(&v)) return fail("truncated or invalid element tags");
        // Tag 0 is the physical group, tag 1 the elementary entity.
        if (k == 0) physical = v;
        if (k == 1 || ntags == 1) entity = v;
      }
      if (type != kGmshHexahedron && type != kGmshHexahedron20) {
        const ElementKind kind = element_kind(type);
        if (kind.dim < 0 || kind.dim > 2 || physical <= 0) {
          in_.skip_line();
          ++skipped_[kind.dim < 3 ? 0 : 1];
          continue;
        }
        nodes.resize(static_cast<std::size_t>(kind.nodes));
        for (auto& v : nodes)
          if (!in_.number(&v)) return fail("truncated or invalid element line");
        if (!add_element(tag, type, entity, nodes, physical)) return false;
        continue;
      }
      nodes.resize(type == kGmshHexahedron ? 8 : 20);
      for (auto& v : nodes)
        if (!in_.number(&v)) return fail("truncated or invalid hexahedron line");
      if (!add_element(tag, type, entity, nodes)) return false;
    }
    return true;
  }

  Cursor in_;
  ReadMeshResult* result_;
  bool v4_ = false;
  bool binary_ = false;
  int data_size_ = 8;
  bool have_nodes_ = false;
  std::unordered_map<std::uint64_t, std::int32_t> node_index_;
  std::uint64_t skipped_[2] = {0, 0};  // lower-dimensional, other volume elements
  std::map<std::pair<int, int>, core::NodeClass> physical_entity_;  // (dim, tag) -> entity
  std::map<std::pair<int, int>, std::vector<std::int32_t>> entity_physicals_;  // MSH 4
  std::unordered_map<std::int32_t, core::NodeClass> node_class_;  // from boundary elements
  struct Hex {
    std::uint64_t tag;
    core::HexNodes nodes;
    std::int32_t sub_volume;
    core::MidEdgeNodes mid;
    bool quadratic;
  };
  std::vector<Hex> hexes_;
};

}  // namespace

ReadMeshResult read_msh(const std::string& path) {
  ReadMeshResult result;
  std::string data;
  if (!detail::load_file(path, &data, &result.diagnostics)) return result;
  result.ok = MshReader(data, &result).read();
  if (!result.ok) result.mesh = core::HexMesh();
  return result;
}

}  // namespace vorohex::io
