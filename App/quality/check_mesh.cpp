#include "quality/check_mesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

#include "quality/detail/parallel.h"
#include "quality/quadratic_jacobian.h"
#include "quality/scaled_jacobian.h"

namespace vorohex::quality {
namespace {

using core::HexMesh;
using core::NodeClass;
using core::Vec3;

constexpr std::size_t kListHexes = 10;
// Below this a positive scaled Jacobian is rounding, not an element: the hex is flat.
constexpr double kDegenerateScaledJacobian = 1e-6;
constexpr std::size_t kListNodes = 5;

// "3, 7, 12 and 4 more"
std::string list_indices(const std::vector<std::size_t>& shown, std::size_t total) {
  std::string s;
  for (std::size_t i = 0; i < shown.size(); ++i) {
    if (i) s += ", ";
    s += std::to_string(shown[i]);
  }
  if (total > shown.size()) s += " and " + std::to_string(total - shown.size()) + " more";
  return s;
}

std::string number(double v) {
  std::ostringstream os;
  os.precision(9);
  os << v;
  return os.str();
}

bool valid_node_index(std::int32_t n, std::size_t num_nodes) {
  return n >= 0 && static_cast<std::size_t>(n) < num_nodes;
}

bool has_repeated_node(const core::HexNodes& h) {
  for (int i = 0; i < 8; ++i)
    for (int j = i + 1; j < 8; ++j)
      if (h[i] == h[j]) return true;
  return false;
}

// A quad key grouped by its smallest node id (the CSR bucket); the three larger ids sorted.
struct QuadEntry {
  std::int32_t b, c, d;
  std::uint32_t quad;  // hex * 6 + local face
  bool operator<(const QuadEntry& o) const {
    if (b != o.b) return b < o.b;
    if (c != o.c) return c < o.c;
    return d < o.d;
  }
  bool same_key(const QuadEntry& o) const { return b == o.b && c == o.c && d == o.d; }
};

std::array<std::int32_t, 4> quad_nodes(const HexMesh& mesh, std::uint32_t quad) {
  const auto& h = mesh.hexes()[quad / 6];
  const auto& f = core::kHexFaces[quad % 6];
  return {h[f[0]], h[f[1]], h[f[2]], h[f[3]]};
}

// The direction in which a hex traverses one of its quads, as seen from the quad's smallest
// node: +1 when the following node is smaller than the preceding one, else -1.
int quad_turn(const HexMesh& mesh, std::uint32_t quad) {
  const auto n = quad_nodes(mesh, quad);
  const int p = static_cast<int>(std::min_element(n.begin(), n.end()) - n.begin());
  return n[(p + 1) % 4] < n[(p + 3) % 4] ? 1 : -1;
}

// Conformity: every quad keyed by its sorted node ids. Bucketing by the smallest id (a
// counting sort) leaves only tiny per-node sorts, so millions of quads take well under 1 s.
// Returns the boundary quads (hex * 6 + face); quads with a repeated node are no faces.
std::vector<std::uint32_t> classify_quads(const HexMesh& mesh, CheckReport& report,
                                          std::vector<std::size_t>& non_manifold_hexes,
                                          std::vector<std::size_t>& folded_hexes) {
  const auto& hexes = mesh.hexes();
  const std::size_t num_nodes = mesh.num_nodes();
  auto sorted_quad = [&](std::uint32_t q) {
    auto n = quad_nodes(mesh, q);
    // Sorting network for four ids (faster than std::sort on six million tiny arrays).
    auto order = [&](int i, int j) {
      if (n[j] < n[i]) std::swap(n[i], n[j]);
    };
    order(0, 1);
    order(2, 3);
    order(0, 2);
    order(1, 3);
    order(1, 2);
    return n;
  };
  std::vector<std::uint32_t> offsets(num_nodes + 1, 0);
  const std::uint32_t num_quads = static_cast<std::uint32_t>(hexes.size() * 6);
  for (std::uint32_t q = 0; q < num_quads; ++q) {
    const auto n = sorted_quad(q);
    if (n[0] != n[1] && n[1] != n[2] && n[2] != n[3]) ++offsets[n[0] + 1];
  }
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  std::vector<QuadEntry> entries(offsets.back());
  std::vector<std::uint32_t> fill(offsets.begin(), offsets.end() - 1);
  for (std::uint32_t q = 0; q < num_quads; ++q) {
    const auto n = sorted_quad(q);
    if (n[0] != n[1] && n[1] != n[2] && n[2] != n[3]) entries[fill[n[0]]++] = {n[1], n[2], n[3], q};
  }
  std::vector<std::uint32_t> boundary;
  for (std::size_t node = 0; node < num_nodes; ++node) {
    const auto first = entries.begin() + offsets[node], last = entries.begin() + offsets[node + 1];
    std::sort(first, last);
    for (auto run = first; run != last;) {
      auto end = run + 1;
      while (end != last && end->same_key(*run)) ++end;
      const auto shared = end - run;
      if (shared == 1) {
        boundary.push_back(run->quad);
      } else if (shared == 2) {
        ++report.interior_quads;
        // Two hexes on opposite sides of a quad traverse it in opposite directions; the
        // same direction means they overlap (a fold that scaled Jacobians cannot see).
        if (quad_turn(mesh, run->quad) == quad_turn(mesh, (run + 1)->quad)) {
          ++report.folded_quads;
          if (folded_hexes.size() < kListHexes) folded_hexes.push_back(run->quad / 6);
        }
      } else {
        ++report.non_manifold_quads;
        for (auto it = run; it != end && non_manifold_hexes.size() < kListHexes; ++it)
          non_manifold_hexes.push_back(it->quad / 6);
      }
      run = end;
    }
  }
  report.boundary_quads = boundary.size();
  std::sort(boundary.begin(), boundary.end());  // deterministic order for later sums
  return boundary;
}

// Edges of the boundary quads: each must lie in exactly two of them.
void check_boundary_edges(const HexMesh& mesh, const std::vector<std::uint32_t>& boundary,
                          CheckReport& report) {
  std::vector<std::uint64_t> keys;
  keys.reserve(boundary.size() * 4);
  for (std::uint32_t q : boundary) {
    const auto n = quad_nodes(mesh, q);
    for (int i = 0; i < 4; ++i) {
      const auto a = static_cast<std::uint64_t>(std::min(n[i], n[(i + 1) % 4]));
      const auto b = static_cast<std::uint64_t>(std::max(n[i], n[(i + 1) % 4]));
      keys.push_back((a << 32) | b);
    }
  }
  std::sort(keys.begin(), keys.end());
  std::size_t single = 0, multiple = 0;
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i + 1;
    while (j < keys.size() && keys[j] == keys[i]) ++j;
    if (j - i == 1) ++single;
    if (j - i > 2) ++multiple;
    i = j;
  }
  report.open_boundary_edges = single + multiple;
  if (report.open_boundary_edges)
    report.diagnostics.push_back(core::make_error(
        "open_boundary", "The boundary surface is not closed: " + std::to_string(single) +
                             " boundary edges lie in one boundary quad and " +
                             std::to_string(multiple) + " in more than two"));
}

// False (with the error) when a hexahedron refers to a node the mesh does not have.
bool check_node_indices(const HexMesh& mesh, CheckReport& report) {
  const auto& hexes = mesh.hexes();
  std::vector<std::size_t> bad;
  std::size_t count = 0;
  for (std::size_t h = 0; h < hexes.size(); ++h)
    for (std::int32_t n : hexes[h])
      if (!valid_node_index(n, mesh.num_nodes())) {
        if (bad.size() < kListHexes) bad.push_back(h);
        ++count;
        break;
      }
  if (count)
    report.diagnostics.push_back(core::make_error(
        "invalid_node_index", std::to_string(count) +
                                  " hexahedra refer to nodes that do not exist (hexes " +
                                  list_indices(bad, count) + ")"));
  return count == 0;
}

// Quads shared by two hexes on one side, by more than two, and boundary edges not in
// exactly two boundary quads, counted and named. Returns the boundary quads.
std::vector<std::uint32_t> check_conformity(const HexMesh& mesh, CheckReport& report) {
  std::vector<std::size_t> non_manifold_hexes, folded_hexes;
  std::vector<std::uint32_t> boundary =
      classify_quads(mesh, report, non_manifold_hexes, folded_hexes);
  if (report.folded_quads)
    report.diagnostics.push_back(core::make_error(
        "overlapping_elements",
        std::to_string(report.folded_quads) +
            " inner quads are shared by two hexahedra lying on the same side of them: the "
            "elements overlap (hexes " +
            list_indices(folded_hexes, report.folded_quads) + ")"));
  if (report.non_manifold_quads)
    report.diagnostics.push_back(core::make_error(
        "non_manifold_faces", std::to_string(report.non_manifold_quads) +
                                  " quads are shared by more than two hexahedra (hexes " +
                                  list_indices(non_manifold_hexes, non_manifold_hexes.size()) +
                                  ")"));
  check_boundary_edges(mesh, boundary, report);
  return boundary;
}

bool class_in_range(NodeClass c, const occ::Solid* cad, int num_vertices, int num_edges,
                    int num_faces) {
  if (c.dim == 3) return true;
  if (c.dim < 0 || c.dim > 3 || c.id < 1) return false;
  if (!cad) return true;
  const int limit = c.dim == 0 ? num_vertices : c.dim == 1 ? num_edges : num_faces;
  return c.id <= limit;
}

std::string class_name(NodeClass c) {
  if (c.dim == 0) return core::entity_name(core::VertexId(c.id));
  if (c.dim == 1) return core::entity_name(core::EdgeId(c.id));
  return core::entity_name(core::FaceId(c.id));
}

// The CAD part: node distances to their entities, and mesh volume against CAD volume.
void check_against_cad(const HexMesh& mesh, const occ::Solid& cad, const CheckOptions& options,
                       const std::vector<std::uint32_t>& boundary,
                       const std::vector<char>& class_ok, CheckReport& report) {
  report.has_cad = true;
  report.cad_volume = cad.volume();
  const double diagonal = cad.diagonal();
  // Within the CAD's own tolerance a point is on it (OCCT's convention; healed solids can
  // carry tolerances above the relative allowance).
  const double distance_tol = std::max(options.distance_rel_tol * diagonal, cad.tolerance());
  const auto& points = mesh.points();
  const auto& classes = mesh.node_classes();

  // Faces around each edge and vertex, to find the face a boundary quad lies on.
  const int nv = cad.num_vertices(), ne = cad.num_edges();
  std::vector<std::vector<int>> edge_faces(ne + 1), vertex_faces(nv + 1);
  for (core::EdgeId e : cad.edges()) {
    for (core::FaceId f : cad.edge_faces(e)) {
      edge_faces[e.value()].push_back(f.value());
      for (core::VertexId v : {cad.edge_first_vertex(e), cad.edge_last_vertex(e)})
        if (v.valid() && v.value() <= nv) vertex_faces[v.value()].push_back(f.value());
    }
  }
  for (auto* lists : {&edge_faces, &vertex_faces})
    for (auto& l : *lists) {
      std::sort(l.begin(), l.end());
      l.erase(std::unique(l.begin(), l.end()), l.end());
    }

  // Node distances: boundary nodes and every node classified on a CAD entity.
  std::vector<char> on_boundary(mesh.num_nodes(), 0);
  for (std::uint32_t q : boundary)
    for (std::int32_t n : quad_nodes(mesh, q)) on_boundary[n] = 1;
  std::vector<double> distance(mesh.num_nodes(), 0.0);
  std::vector<std::size_t> off;
  for (std::size_t n = 0; n < mesh.num_nodes(); ++n) {
    const NodeClass c = classes[n];
    const bool classified = class_ok[n] && c.dim < 3;
    if (!classified && !on_boundary[n]) continue;
    const Vec3& p = points[n];
    double d;
    if (!classified)
      d = cad.distance_to_boundary(p);
    else if (c.dim == 0)
      d = cad.distance_to_vertex(core::VertexId(c.id), p);
    else if (c.dim == 1)
      d = cad.distance_to_edge(core::EdgeId(c.id), p);
    else
      d = cad.distance_to_face(core::FaceId(c.id), p);
    distance[n] = d;
    report.max_boundary_distance = std::max(report.max_boundary_distance, d);
    if (!(d <= distance_tol)) off.push_back(n);
  }
  report.max_boundary_distance_rel = diagonal > 0 ? report.max_boundary_distance / diagonal : 0;
  if (!off.empty()) {
    std::stable_sort(off.begin(), off.end(),
                     [&](std::size_t a, std::size_t b) { return distance[a] > distance[b]; });
    std::vector<std::size_t> shown(off.begin(), off.begin() + std::min(off.size(), kListNodes));
    std::vector<std::string> entities;
    for (std::size_t n : shown)
      if (class_ok[n] && classes[n].dim < 3) entities.push_back(class_name(classes[n]));
    std::sort(entities.begin(), entities.end());
    entities.erase(std::unique(entities.begin(), entities.end()), entities.end());
    report.diagnostics.push_back(core::make_error(
        "nodes_off_cad",
        std::to_string(off.size()) + " nodes lie off the CAD boundary (nodes " +
            list_indices(shown, off.size()) + "); worst distance " +
            number(report.max_boundary_distance) + " (" + number(report.max_boundary_distance_rel) +
            " of the diagonal, allowed " + number(distance_tol / diagonal) + ")",
        std::move(entities)));
  }

  // Chord allowance: a boundary quad whose nodes lie on the CAD approximates the surface
  // within (area * centre distance). Quads with nodes off the CAD are no chords of it and
  // get no allowance, or a mesh with a hole would excuse its own missing volume.
  double chord = 0, on_cad_area = 0;
  std::size_t interface_quads = 0;
  std::vector<int> interface_faces;
  auto node_faces = [&](std::int32_t n) -> std::vector<int> {
    const NodeClass c = classes[n];
    if (!class_ok[n] || c.dim == 3) return {};
    if (c.dim == 2) return {c.id};
    return c.dim == 1 ? edge_faces[c.id] : vertex_faces[c.id];
  };
  // Boundary quads that span two faces meeting at an edge with none of their nodes on it:
  // the mesh cuts the corner off there. Across an edge that is not tangent they are no
  // chords of the surface, and the chord allowance below leaves them out (it counted them,
  // their centres off the CAD by about their size, so a mesh whose nodes are all on the CAD
  // passed with a corner cut off: HexMe i22, a boss's rim, 0.8 % of the volume; n10's grid
  // mesh 5.9 %; a quad across a 20-degree ridge excused twice what it cut off). Those across
  // a sharp edge (normals more than 30 degrees apart at its middle) are named.
  std::map<std::pair<int, int>, std::vector<int>> edges_between;  // faces -> edges
  for (core::EdgeId e : cad.edges())
    if (edge_faces[e.value()].size() == 2)
      edges_between[{edge_faces[e.value()][0], edge_faces[e.value()][1]}].push_back(e.value());
  // Per edge, the angle between its faces' normals at its middle: 0 up to 10 degrees
  // (tangent, as a chord of a curved face turns across a quad), 1 up to 30, 2 sharp.
  std::vector<signed char> bend(ne + 1, -1);  // -1: not looked at yet
  auto bend_of = [&](int e) {
    if (bend[e] < 0) {
      const core::EdgeId id(e);
      const Vec3 m = cad.edge_points_by_length(id, 2)[1];
      const double cosine = cad.face_normal(core::FaceId(edge_faces[e][0]), m)
                                .dot(cad.face_normal(core::FaceId(edge_faces[e][1]), m));
      bend[e] = cad.edge_is_degenerated(id)    ? 0
                : cosine < std::cos(M_PI / 6)  ? 2
                : cosine < std::cos(M_PI / 18) ? 1
                                               : 0;
    }
    return bend[e];
  };
  std::size_t across_quads = 0;
  std::set<int> across_edges;
  auto on_edge = [&](std::int32_t node, int e) {
    const NodeClass c = classes[node];
    if (!class_ok[node]) return false;
    if (c.dim == 1) return c.id == e;
    const core::EdgeId id(e);
    return c.dim == 0 &&
           (c.id == cad.edge_first_vertex(id).value() || c.id == cad.edge_last_vertex(id).value());
  };
  // Two faces can meet along several edges (a rim of two half circles): a quad with a node
  // on any of them follows the faces' border there. True when the quad crosses an edge that
  // is not tangent (no chord then); one across a sharp edge is counted and named.
  auto count_across = [&](const std::array<std::int32_t, 4>& n) -> bool {
    // The pairs of faces two of its nodes lie on, each once.
    std::set<std::pair<int, int>> pairs;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        if (i != j)
          for (int a : node_faces(n[i]))
            for (int b : node_faces(n[j]))
              if (a < b) pairs.insert({a, b});
    std::set<int> sharp;
    bool bent = false;
    for (const auto& pair : pairs) {
      const auto it = edges_between.find(pair);
      if (it == edges_between.end()) continue;
      bool on = false;
      // On one by its class, or lying on one (a node on the edge given a face).
      for (int e : it->second)
        for (std::int32_t k : n)
          on = on || on_edge(k, e) ||
               cad.distance_to_edge(core::EdgeId(e), points[k]) <= distance_tol;
      if (on) continue;
      for (int e : it->second) {
        bent = bent || bend_of(e) > 0;
        if (bend_of(e) == 2) sharp.insert(e);
      }
    }
    if (!sharp.empty()) {
      ++across_quads;
      across_edges.insert(sharp.begin(), sharp.end());
    }
    return bent;
  };
  auto adjacent = [&](const std::vector<int>& fa, const std::vector<int>& fb) {
    for (int a : fa)
      for (int b : fb)
        if (a == b || edges_between.count({std::min(a, b), std::max(a, b)})) return true;
    return false;
  };
  // Only where every node is classified on the CAD (a mesh read from a file, unclassified, is
  // measured against the whole boundary: its quads keep their allowance).
  auto bridges = [&](const std::array<std::int32_t, 4>& n) {
    std::array<std::vector<int>, 4> faces;
    for (int i = 0; i < 4; ++i)
      if ((faces[i] = node_faces(n[i])).empty()) return false;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (!adjacent(faces[i], faces[j])) return true;
    return false;
  };
  for (std::uint32_t q : boundary) {
    const auto n = quad_nodes(mesh, q);
    bool on_cad = true;
    for (std::int32_t i : n) on_cad = on_cad && distance[i] <= distance_tol;
    if (!on_cad) continue;
    const Vec3 &a = points[n[0]], &b = points[n[1]], &c = points[n[2]], &d = points[n[3]];
    // Mean of the two diagonal splittings, so the area does not depend on the start node.
    const double area = 0.25 * ((b - a).cross(c - a).norm() + (c - a).cross(d - a).norm() +
                                (b - a).cross(d - a).norm() + (c - b).cross(d - b).norm());
    const Vec3 centre = 0.25 * (a + b + c + d);
    on_cad_area += area;
    std::vector<int> common = node_faces(n[0]);
    for (int i = 1; i < 4 && !common.empty(); ++i) {
      const std::vector<int> other = node_faces(n[i]);
      std::vector<int> kept;
      std::set_intersection(common.begin(), common.end(), other.begin(), other.end(),
                            std::back_inserter(kept));
      common.swap(kept);
    }
    if (common.empty() && count_across(n)) continue;
    // Two of its nodes on faces that do not meet (no common face, no edge between them): it
    // bridges the solid, no chord of its surface (a grid mesh that lost the material under a
    // blind pocket's floor lined the hole with quads from the floor to the bottom face, and
    // their allowance excused the missing 7.8 % of the volume).
    if (common.empty() && bridges(n)) continue;
    const double dist = common.empty() ? cad.distance_to_boundary(centre)
                                       : cad.distance_to_face(core::FaceId(common[0]), centre);
    chord += area * dist;
    // A face two solids share lies inside the whole: a boundary quad there means the two
    // solids' meshes do not match on it.
    if (!common.empty() && std::all_of(common.begin(), common.end(), [&](int f) {
          return cad.face_is_interface(core::FaceId(f));
        })) {
      ++interface_quads;
      interface_faces.push_back(common[0]);
    }
  }
  if (interface_quads > 0) {
    std::sort(interface_faces.begin(), interface_faces.end());
    interface_faces.erase(std::unique(interface_faces.begin(), interface_faces.end()),
                          interface_faces.end());
    std::vector<std::string> names;
    for (int f : interface_faces) names.push_back(core::entity_name(core::FaceId(f)));
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    report.diagnostics.push_back(core::make_error(
        "non_conforming_interface",
        std::to_string(interface_quads) + " boundary quads lie on faces shared by two solids (" +
            list + "): the solids' meshes do not match there",
        std::move(names)));
  }
  if (across_quads > 0) {
    std::vector<std::string> names;
    for (int e : across_edges) names.push_back(core::entity_name(core::EdgeId(e)));
    std::string list;
    for (std::size_t i = 0; i < names.size() && i < 8; ++i)
      list += (list.empty() ? "" : ", ") + names[i];
    if (names.size() > 8) list += ", ...";
    report.diagnostics.push_back(core::make_warning(
        "boundary_across_edges",
        std::to_string(across_quads) +
            " boundary quads span two faces across a sharp model edge with none of their nodes "
            "on it (" +
            list + "): the mesh cuts the corner off there",
        std::move(names)));
  }
  // A CAD tolerance above the distance allowance lets the surface itself move by that much.
  const double tolerance_excess = std::max(0.0, distance_tol - options.distance_rel_tol * diagonal);
  report.volume_allowance =
      options.volume_rel_tol * std::abs(report.cad_volume) + chord + on_cad_area * tolerance_excess;
  const double diff = std::abs(report.mesh_volume - report.cad_volume);
  report.volume_rel_error = report.cad_volume != 0 ? diff / std::abs(report.cad_volume) : diff;
  if (!(diff <= report.volume_allowance))
    report.diagnostics.push_back(core::make_error(
        "volume_mismatch", "Mesh volume " + number(report.mesh_volume) +
                               " differs from the CAD volume " + number(report.cad_volume) +
                               " by " + number(diff) + " (allowed " +
                               number(report.volume_allowance) + ")"));
}

}  // namespace

void CheckOptions::validate() const {
  auto check = [](double v, const char* name) {
    if (std::isnan(v) || v < 0)
      throw std::invalid_argument(std::string("CheckOptions::") + name +
                                  " must be a non-negative number, got " + number(v));
  };
  check(volume_rel_tol, "volume_rel_tol");
  check(distance_rel_tol, "distance_rel_tol");
}

namespace {

// The `count` hexahedra of lowest scaled Jacobian, worst first, with where they are.
std::vector<WorstHex> worst_hexes(const HexMesh& mesh, const std::vector<double>& sj,
                                  std::size_t count) {
  std::vector<std::size_t> order(sj.size());
  for (std::size_t h = 0; h < order.size(); ++h) order[h] = h;
  count = std::min(count, order.size());
  std::partial_sort(
      order.begin(), order.begin() + long(count), order.end(),
      [&](std::size_t a, std::size_t b) { return sj[a] < sj[b] || (sj[a] == sj[b] && a < b); });
  std::vector<WorstHex> out;
  for (std::size_t k = 0; k < count; ++k) {
    WorstHex w;
    w.hex = order[k];
    w.scaled_jacobian = sj[w.hex];
    const auto& nodes = mesh.hexes()[w.hex];
    std::vector<std::pair<int, int>> on;  // (dim, id) of the CAD entities its corners lie on
    for (int c = 0; c < 8; ++c) {
      const core::NodeId n(nodes[c]);
      w.centre += mesh.point(n) / 8.0;
      const core::NodeClass nc = mesh.node_class(n);
      if (nc.dim >= 0 && nc.dim <= 2 && nc.id > 0) on.emplace_back(nc.dim, nc.id);
    }
    std::sort(on.begin(), on.end());
    on.erase(std::unique(on.begin(), on.end()), on.end());
    for (const auto& [dim, id] : on)
      w.entities.push_back(dim == 0   ? core::entity_name(core::VertexId(id))
                           : dim == 1 ? core::entity_name(core::EdgeId(id))
                                      : core::entity_name(core::FaceId(id)));
    out.push_back(std::move(w));
  }
  return out;
}

}  // namespace

CheckReport check_mesh(const HexMesh& mesh, const occ::Solid* cad, const CheckOptions& options,
                       std::vector<double>* scaled_jacobian_out) {
  options.validate();
  CheckReport report;
  report.nodes = mesh.num_nodes();
  report.hexes = mesh.num_hexes();
  report.order = mesh.order();
  const auto& hexes = mesh.hexes();
  auto& diags = report.diagnostics;

  // Node indices first: nothing else can be measured if a hex points outside the mesh.
  if (!check_node_indices(mesh, report)) return report;

  // Element quality.
  std::vector<double> local_sj;
  std::vector<double>& sj = scaled_jacobian_out ? *scaled_jacobian_out : local_sj;
  sj = scaled_jacobians(mesh);
  report.scaled_jacobian = quality_stats(sj);
  report.non_positive = report.scaled_jacobian.inverted;
  report.worst = worst_hexes(mesh, sj, 3);
  if (report.non_positive) {
    std::vector<std::size_t> shown;
    for (std::size_t h = 0; h < sj.size() && shown.size() < kListHexes; ++h)
      if (!(sj[h] > 0)) shown.push_back(h);
    diags.push_back(
        core::make_error("inverted_elements", std::to_string(report.non_positive) +
                                                  " hexahedra have a scaled Jacobian <= 0 (hexes " +
                                                  list_indices(shown, report.non_positive) + ")"));
  }
  {
    // Positive only by rounding: a hexahedron flattened onto a face or an edge (a smoothing
    // that untangled it to just above zero) is no usable element.
    std::vector<std::size_t> shown;
    for (std::size_t h = 0; h < sj.size(); ++h)
      if (sj[h] > 0 && sj[h] < kDegenerateScaledJacobian) {
        ++report.degenerate;
        if (shown.size() < kListHexes) shown.push_back(h);
      }
    if (report.degenerate)
      diags.push_back(core::make_error(
          "degenerate_elements", std::to_string(report.degenerate) +
                                     " hexahedra have a scaled Jacobian below 1e-6, flat up to "
                                     "rounding (hexes " +
                                     list_indices(shown, report.degenerate) + ")"));
  }
  {
    std::vector<std::size_t> shown;
    std::size_t count = 0;
    for (std::size_t h = 0; h < hexes.size(); ++h)
      if (has_repeated_node(hexes[h])) {
        if (shown.size() < kListHexes) shown.push_back(h);
        ++count;
      }
    if (count)
      diags.push_back(core::make_error(
          "degenerate_elements", std::to_string(count) + " hexahedra use a node twice (hexes " +
                                     list_indices(shown, count) + ")"));
  }

  // Conformity and a closed boundary.
  const std::vector<std::uint32_t> boundary = check_conformity(mesh, report);

  // Second order: every hexahedron needs its 12 mid-edge nodes and a positive Jacobian at
  // the 27 Gauss points (the corners' scaled Jacobian above does not see a curved edge fold).
  const auto& mid = mesh.mid_edge_nodes();
  if (!mid.empty() && mid.size() != hexes.size()) {
    diags.push_back(core::make_error("bad_mid_edge_nodes",
                                     std::to_string(mid.size()) + " mid-edge node lists for " +
                                         std::to_string(hexes.size()) + " hexahedra"));
    return report;
  }
  if (!mid.empty()) {
    std::vector<std::size_t> shown;
    std::size_t count = 0;
    for (std::size_t h = 0; h < hexes.size(); ++h) {
      bool index_ok = true;
      for (std::int32_t n : mid[h]) index_ok = index_ok && valid_node_index(n, mesh.num_nodes());
      if (!index_ok) {
        diags.push_back(core::make_error(
            "invalid_node_index",
            "hexahedron " + std::to_string(h) + " refers to a mid-edge node that does not exist"));
        return report;
      }
      std::array<core::Vec3, 20> nodes;
      for (int i = 0; i < 8; ++i) nodes[i] = mesh.points()[hexes[h][i]];
      for (int i = 0; i < 12; ++i) nodes[8 + i] = mesh.points()[mid[h][i]];
      if (!(quadratic_hex_jacobian(nodes).min_det > 0)) {
        if (shown.size() < kListHexes) shown.push_back(h);
        ++count;
      }
    }
    report.non_positive_gauss = count;
    if (count)
      diags.push_back(
          core::make_error("inverted_quadratic_elements",
                           std::to_string(count) +
                               " 20-node hexahedra have a Jacobian <= 0 at a Gauss point (hexes " +
                               list_indices(shown, count) + ")"));
  }

  std::vector<char> used(mesh.num_nodes(), 0);
  for (const auto& h : hexes)
    for (std::int32_t n : h) used[n] = 1;
  for (const auto& m : mid)
    for (std::int32_t n : m) used[n] = 1;
  report.unused_nodes = static_cast<std::size_t>(std::count(used.begin(), used.end(), 0));
  if (report.unused_nodes)
    diags.push_back(core::make_warning(
        "unused_nodes", std::to_string(report.unused_nodes) + " nodes belong to no hexahedron"));

  // Classification: dimension 0..3 and, for model entities, a 1-based id within the solid.
  const int nv = cad ? cad->num_vertices() : 0, ne = cad ? cad->num_edges() : 0,
            nf = cad ? cad->num_faces() : 0;
  std::vector<char> class_ok(mesh.num_nodes(), 1);
  {
    std::vector<std::size_t> shown;
    std::size_t count = 0;
    const auto& classes = mesh.node_classes();
    for (std::size_t n = 0; n < classes.size(); ++n)
      if (!class_in_range(classes[n], cad, nv, ne, nf)) {
        class_ok[n] = 0;
        if (shown.size() < kListHexes) shown.push_back(n);
        ++count;
      }
    if (count)
      diags.push_back(core::make_error(
          "bad_classification", std::to_string(count) +
                                    " nodes are classified on entities that do not exist (nodes " +
                                    list_indices(shown, count) + ")"));
  }

  // Volume (always reported; compared with the CAD when there is one).
  report.mesh_volume = mesh_volume(mesh);
  if (cad) {
    try {
      check_against_cad(mesh, *cad, options, boundary, class_ok, report);
    } catch (const std::exception& e) {
      diags.push_back(
          core::make_error("cad_query_failed", std::string("A CAD query failed: ") + e.what()));
    }
  }

  report.valid = !core::has_error(diags);
  return report;
}

double mesh_volume(const HexMesh& mesh) {
  const std::size_t hexes = mesh.num_hexes();
  std::vector<double> partial(detail::num_chunks(hexes, 20000), 0.0);
  detail::parallel_chunks(hexes, 20000, [&](std::size_t chunk, std::size_t b, std::size_t e) {
    double sum = 0;
    for (std::size_t h = b; h < e; ++h)
      sum += hex_volume(mesh.corners(core::HexId(static_cast<std::int32_t>(h))));
    partial[chunk] = sum;
  });
  return std::accumulate(partial.begin(), partial.end(), 0.0);
}

CheckReport check_topology(const HexMesh& mesh) {
  CheckReport report;
  report.nodes = mesh.num_nodes();
  report.hexes = mesh.num_hexes();
  report.order = mesh.order();
  if (check_node_indices(mesh, report)) check_conformity(mesh, report);
  return report;
}

}  // namespace vorohex::quality
