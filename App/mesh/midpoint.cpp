#include "mesh/midpoint.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "core/option_checks.h"
#include "mesh/detail/refine.h"
#include "mesh/detail/tet_to_hex.h"
#include "quality/scaled_jacobian.h"

namespace vorohex::mesh {

using core::EdgeId;
using core::FaceId;
using core::HexMesh;
using core::NodeClass;
using core::Vec3;
using core::VertexId;

void MidpointOptions::validate() const {
  core::require_positive("MidpointOptions.size", size);
  core::require_at_least("MidpointOptions.max_intervals", max_intervals, 1);
}

namespace {

// The solid as a polyhedron: 0-based vertex, edge and face indices (MapShapes index - 1).
struct Polyhedron {
  std::vector<Vec3> vertex;
  std::vector<std::array<int, 2>> edge;
  std::vector<std::vector<int>> face_edges;
  std::vector<Vec3> normal;  // outward
  std::vector<double> offset;
  std::map<std::pair<int, int>, int> edge_of_faces;  // (f, g) with f < g -> edge
};

VertexId vid(int i) {
  return VertexId(i + 1);
}
EdgeId eid(int i) {
  return EdgeId(i + 1);
}
FaceId fid(int i) {
  return FaceId(i + 1);
}

// Builds the polyhedron or says why the solid is not a convex one.
std::string read_polyhedron(const core::MeshDomain& s, Polyhedron& p) {
  const double tol = 1e-7 * s.diagonal();
  for (VertexId v : s.vertices()) p.vertex.push_back(s.vertex_point(v));
  for (EdgeId e : s.edges()) {
    if (s.edge_is_degenerated(e)) return core::entity_name(e) + " is degenerate";
    const int a = s.edge_first_vertex(e).value() - 1, b = s.edge_last_vertex(e).value() - 1;
    if (a == b || std::abs((p.vertex[a] - p.vertex[b]).norm() - s.edge_length(e)) > tol)
      return core::entity_name(e) + " is not straight";
    p.edge.push_back({a, b});
    const std::vector<FaceId> faces = s.edge_faces(e);
    if (faces.size() != 2) return core::entity_name(e) + " does not bound two faces";
    const int f = std::min(faces[0].value(), faces[1].value()) - 1;
    const int g = std::max(faces[0].value(), faces[1].value()) - 1;
    p.edge_of_faces[{f, g}] = e.value() - 1;
  }
  for (FaceId f : s.faces()) {
    if (!s.face_is_planar(f)) return core::entity_name(f) + " is not planar";
    const auto wires = s.face_wires(f);
    if (wires.size() != 1) return core::entity_name(f) + " has a hole";
    std::vector<int> edges;
    for (const core::OrientedEdge& oe : wires[0]) edges.push_back(oe.edge.value() - 1);
    const Vec3 a = p.vertex[p.edge[edges[0]][0]];
    const Vec3 n = s.face_normal(f, a);
    p.face_edges.push_back(edges);
    p.normal.push_back(n);
    p.offset.push_back(n.dot(a));
  }
  for (std::size_t f = 0; f < p.normal.size(); ++f)
    for (std::size_t v = 0; v < p.vertex.size(); ++v)
      if (p.normal[f].dot(p.vertex[v]) - p.offset[f] > tol)
        return "not convex: " + core::entity_name(vid(static_cast<int>(v))) +
               " lies outside the plane of " + core::entity_name(fid(static_cast<int>(f)));
  return {};
}

std::vector<int> face_vertices(const Polyhedron& p, int f) {
  std::vector<int> out;
  for (int e : p.face_edges[f])
    for (int v : p.edge[e])
      if (std::find(out.begin(), out.end(), v) == out.end()) out.push_back(v);
  return out;
}

Vec3 average(const Polyhedron& p, const std::vector<int>& vertices) {
  Vec3 c = Vec3::Zero();
  for (int v : vertices) c += p.vertex[v];
  return c / static_cast<double>(vertices.size());
}

bool every_vertex_has_three_edges(const Polyhedron& p) {
  std::vector<int> degree(p.vertex.size(), 0);
  for (const auto& e : p.edge) ++degree[e[0]], ++degree[e[1]];
  return std::all_of(degree.begin(), degree.end(), [](int d) { return d == 3; });
}

double det3(const Vec3& a, const Vec3& b, const Vec3& c) {
  return a.dot(b.cross(c));
}

// Coarse nodes shared by both variants: vertices, face centres and the cell centre (the
// volume centroid of the cone decomposition, inside a convex cell).
struct CoarseBase {
  std::vector<int> face_node;
  int centre = -1;
};

CoarseBase add_base_nodes(const Polyhedron& p, HexMesh& m) {
  CoarseBase b;
  for (std::size_t v = 0; v < p.vertex.size(); ++v)
    m.add_node(p.vertex[v], NodeClass::on(vid(static_cast<int>(v))));
  std::vector<Vec3> centre(p.face_edges.size());
  Vec3 all = Vec3::Zero();
  for (std::size_t f = 0; f < p.face_edges.size(); ++f) {
    centre[f] = average(p, face_vertices(p, static_cast<int>(f)));
    b.face_node.push_back(
        static_cast<int>(m.add_node(centre[f], NodeClass::on(fid(static_cast<int>(f)))).value()));
  }
  for (const Vec3& v : p.vertex) all += v;
  all /= static_cast<double>(p.vertex.size());
  Vec3 weighted = Vec3::Zero();
  double volume = 0;
  for (std::size_t f = 0; f < p.face_edges.size(); ++f)
    for (int e : p.face_edges[f]) {
      const Vec3 &a = p.vertex[p.edge[e][0]], &c = p.vertex[p.edge[e][1]];
      const double v = std::abs(det3(centre[f] - all, a - all, c - all)) / 6;
      weighted += v * (all + centre[f] + a + c) / 4;
      volume += v;
    }
  b.centre = static_cast<int>(m.add_node(volume > 0 ? Vec3(weighted / volume) : all).value());
  return b;
}

// One hexahedron per vertex of a polyhedron whose vertices all have three edges.
HexMesh per_vertex_cells(const Polyhedron& p) {
  HexMesh m;
  const CoarseBase b = add_base_nodes(p, m);
  std::vector<int> mid(p.edge.size());
  for (std::size_t e = 0; e < p.edge.size(); ++e)
    mid[e] = static_cast<int>(m.add_node((p.vertex[p.edge[e][0]] + p.vertex[p.edge[e][1]]) / 2,
                                         NodeClass::on(eid(static_cast<int>(e))))
                                  .value());
  auto face_with = [&](int e1, int e2) {
    for (std::size_t f = 0; f < p.face_edges.size(); ++f) {
      const auto& fe = p.face_edges[f];
      if (std::count(fe.begin(), fe.end(), e1) && std::count(fe.begin(), fe.end(), e2))
        return b.face_node[f];
    }
    return -1;
  };
  for (std::size_t v = 0; v < p.vertex.size(); ++v) {
    std::vector<int> at;
    for (std::size_t e = 0; e < p.edge.size(); ++e)
      if (p.edge[e][0] == static_cast<int>(v) || p.edge[e][1] == static_cast<int>(v))
        at.push_back(static_cast<int>(e));
    const int a = at[0], bb = at[1], c = at[2];
    detail::add_hex_positive_at_corner0(m, {static_cast<int>(v), mid[a], face_with(a, bb), mid[bb],
                                            mid[c], face_with(c, a), b.centre, face_with(bb, c)});
  }
  return m;
}

// A face's vertices in order around it.
std::vector<int> face_cycle(const Polyhedron& p, int f) {
  const std::vector<int>& fe = p.face_edges[f];
  std::vector<int> cycle{p.edge[fe[0]][0], p.edge[fe[0]][1]};
  std::vector<char> used(fe.size(), 0);
  used[0] = 1;
  for (bool grew = true; grew && cycle.size() < fe.size();) {
    grew = false;
    for (std::size_t i = 1; i < fe.size() && !grew; ++i) {
      if (used[i]) continue;
      const auto [a, b] = p.edge[fe[i]];
      const int prev = cycle[cycle.size() - 2];
      if (a == cycle.back() && b != prev)
        cycle.push_back(b), used[i] = grew = true;
      else if (b == cycle.back() && a != prev)
        cycle.push_back(a), used[i] = grew = true;
    }
  }
  return cycle;
}

// The smallest scaled Jacobian of the four hexahedra a tetrahedron splits into.
double split_quality(const std::array<Vec3, 4>& corners) {
  HexMesh m;
  for (const Vec3& c : corners) m.add_node(c);
  detail::split_tetrahedra(m, {{0, 1, 2, 3}});
  const std::vector<double> sj = quality::scaled_jacobians(m);
  return *std::min_element(sj.begin(), sj.end());
}

// A way to cut the cell into tetrahedra (indices into the cell's points: its vertices, then
// `extra`), the smallest scaled Jacobian of their hexahedra, and what it is.
struct Tetrahedra {
  std::vector<std::array<int, 4>> tets;
  std::vector<Vec3> extra;  // points added to the vertices (centres), in node order
  std::vector<NodeClass> extra_class;
  double quality = -1;
  std::string name;
};

// Cones from `apex` (a point index) over every face not containing it, each face cut into a
// fan of triangles from the vertex that gives its tetrahedra's hexahedra the best minimum.
// cycles: each face's vertices in order around it (face_cycle).
void add_cones(const std::vector<std::vector<int>>& cycles, const std::vector<Vec3>& points,
               int apex, Tetrahedra& t) {
  t.quality = 1;
  for (const std::vector<int>& cycle : cycles) {
    if (std::find(cycle.begin(), cycle.end(), apex) != cycle.end()) continue;
    const int k = static_cast<int>(cycle.size());
    double best = -2;
    std::vector<std::array<int, 4>> chosen;
    for (int root = 0; root < k; ++root) {
      std::vector<std::array<int, 4>> fan;
      double q = 1;
      for (int i = 1; i + 1 < k; ++i) {
        const std::array<int, 4> tet{apex, cycle[root], cycle[(root + i) % k],
                                     cycle[(root + i + 1) % k]};
        fan.push_back(tet);
        q = std::min(
            q, split_quality({points[tet[0]], points[tet[1]], points[tet[2]], points[tet[3]]}));
      }
      if (q > best + 1e-12) best = q, chosen = fan;
    }
    t.tets.insert(t.tets.end(), chosen.begin(), chosen.end());
    t.quality = std::min(t.quality, best);
  }
}

// The tetrahedra the cell is cut into: of the cell centre, a face centre and an edge (every
// face in triangles around its centre), of the cell centre over each face's fan of
// triangles, or cones from one vertex over the faces away from it - whichever gives the
// hexahedra the best minimum (a square pyramid: 0.17, 0.44, 0.5 - two tetrahedra, split
// along a diagonal of the base; an icosahedron: 0.30, 0.69, 0.26).
Tetrahedra best_tetrahedra(const Polyhedron& p, const CoarseBase& base, const HexMesh& nodes) {
  const int nv = static_cast<int>(p.vertex.size());
  std::vector<Vec3> points(p.vertex.begin(), p.vertex.end());
  const Vec3 centre = nodes.point(core::NodeId(base.centre));
  std::vector<std::vector<int>> cycles;
  for (std::size_t f = 0; f < p.face_edges.size(); ++f)
    cycles.push_back(face_cycle(p, static_cast<int>(f)));
  // Of the centre, a face centre and an edge.
  Tetrahedra best;
  {
    std::vector<Vec3> pts = points;
    best.extra.push_back(centre);
    best.extra_class.push_back(NodeClass::interior());
    pts.push_back(centre);
    best.quality = 1;
    for (std::size_t f = 0; f < p.face_edges.size(); ++f) {
      const int c = static_cast<int>(pts.size());
      pts.push_back(nodes.point(core::NodeId(base.face_node[f])));
      best.extra.push_back(pts.back());
      best.extra_class.push_back(NodeClass::on(fid(static_cast<int>(f))));
      for (int e : p.face_edges[f]) {
        best.tets.push_back({nv, c, p.edge[e][0], p.edge[e][1]});
        best.quality = std::min(
            best.quality, split_quality({centre, pts[c], pts[p.edge[e][0]], pts[p.edge[e][1]]}));
      }
    }
    best.name = "four hexahedra per tetrahedron of centre, face centre and edge";
  }
  {
    Tetrahedra t;
    std::vector<Vec3> pts = points;
    pts.push_back(centre);
    t.extra = {centre};
    t.extra_class = {NodeClass::interior()};
    add_cones(cycles, pts, nv, t);
    t.name = "four hexahedra per tetrahedron of the centre over each face's triangles";
    if (t.quality > best.quality + 1e-9) best = std::move(t);
  }
  for (int v = 0; v < nv; ++v) {
    Tetrahedra t;
    add_cones(cycles, points, v, t);
    t.name = "four hexahedra per tetrahedron of the cones from " + core::entity_name(vid(v)) +
             " over the faces away from it";
    if (t.quality > best.quality + 1e-9) best = std::move(t);
  }
  return best;
}

// The cell cut into tetrahedra (best_tetrahedra), each into four hexahedra (corner, three
// edge midpoints, three face centroids, tetrahedron centroid).
HexMesh tetrahedral_cells(const Polyhedron& p, std::string& name) {
  HexMesh all;
  const CoarseBase b = add_base_nodes(p, all);
  const Tetrahedra t = best_tetrahedra(p, b, all);
  name = t.name;
  HexMesh m;  // the vertices, then only the centres the tetrahedra use
  for (std::size_t v = 0; v < p.vertex.size(); ++v)
    m.add_node(p.vertex[v], NodeClass::on(vid(static_cast<int>(v))));
  for (std::size_t i = 0; i < t.extra.size(); ++i) m.add_node(t.extra[i], t.extra_class[i]);
  detail::split_tetrahedra(m, t.tets);
  return m;
}

double mean_edge_length(const HexMesh& m) {
  static constexpr int kEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                        {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  double sum = 0;
  for (std::size_t h = 0; h < m.num_hexes(); ++h) {
    const auto c = m.corners(core::HexId(static_cast<std::int32_t>(h)));
    for (const auto& e : kEdges) sum += (c[e[0]] - c[e[1]]).norm();
  }
  return sum / (12.0 * static_cast<double>(m.num_hexes()));
}

// Puts every new node on the model entity it lies on: in a convex cell a point on the
// plane of one face is on that face, on two is on their common edge, on three or more is a
// vertex.
void classify(HexMesh& m, const Polyhedron& p, double tol, std::size_t first) {
  for (std::size_t i = first; i < m.num_nodes(); ++i) {
    const core::NodeId id(static_cast<std::int32_t>(i));
    const Vec3& x = m.point(id);
    std::vector<int> on;
    for (std::size_t f = 0; f < p.normal.size(); ++f)
      if (std::abs(p.normal[f].dot(x) - p.offset[f]) < tol) on.push_back(static_cast<int>(f));
    if (on.empty()) continue;
    if (on.size() == 1) {
      m.set_node_class(id, NodeClass::on(fid(on[0])));
      continue;
    }
    if (on.size() == 2) {
      const auto it = p.edge_of_faces.find({on[0], on[1]});
      m.set_node_class(id, it != p.edge_of_faces.end() ? NodeClass::on(eid(it->second))
                                                       : NodeClass::on(fid(on[0])));
      continue;
    }
    int best = 0;
    for (std::size_t v = 1; v < p.vertex.size(); ++v)
      if ((p.vertex[v] - x).norm() < (p.vertex[best] - x).norm()) best = static_cast<int>(v);
    m.set_node_class(id, NodeClass::on(vid(best)));
  }
}

struct Plan {
  Polyhedron poly;
  HexMesh coarse;
  bool per_vertex = false;
  std::string variant;
  int n = 0;
  std::string error;
};

Plan plan(const core::MeshDomain& solid, const MidpointOptions& options) {
  options.validate();
  Plan pl;
  pl.error = read_polyhedron(solid, pl.poly);
  if (!pl.error.empty()) return pl;
  pl.per_vertex = every_vertex_has_three_edges(pl.poly);
  pl.coarse = pl.per_vertex ? per_vertex_cells(pl.poly) : tetrahedral_cells(pl.poly, pl.variant);
  if (pl.per_vertex) pl.variant = "one hexahedron per vertex";
  const double n = std::max(1.0, std::round(mean_edge_length(pl.coarse) / options.size));
  if (n > options.max_intervals) {
    std::ostringstream s;
    s << "midpoint subdivision would split each cell " << n << " times per direction, more than "
      << "max_intervals = " << options.max_intervals;
    pl.error = s.str();
    return pl;
  }
  pl.n = static_cast<int>(n);
  return pl;
}

}  // namespace

Applicability midpoint_applicable(const core::MeshDomain& solid) {
  Polyhedron p;
  const std::string why = read_polyhedron(solid, p);
  return {why.empty(), why};
}

MidpointEstimate midpoint_evaluate(const core::MeshDomain& solid, const MidpointOptions& options) {
  const Plan pl = plan(solid, options);
  MidpointEstimate e;
  if (!pl.error.empty()) return e;
  e.per_vertex = pl.per_vertex;
  e.subdivisions = pl.n;
  e.coarse_hexes = pl.coarse.num_hexes();
  e.nodes = detail::refined_node_count(pl.coarse, pl.n);
  e.hexes = e.coarse_hexes * static_cast<std::size_t>(pl.n) * pl.n * pl.n;
  return e;
}

MidpointResult midpoint_subdivide(const core::MeshDomain& solid, const MidpointOptions& options,
                                  const core::Progress& progress) {
  progress.report("midpoint", 0.0);
  MidpointResult r;
  const Plan pl = plan(solid, options);
  if (!pl.error.empty()) {
    r.diagnostics.push_back(core::make_error(
        "midpoint_not_applicable", "Midpoint subdivision does not apply: " + pl.error + "."));
    return r;
  }
  r.per_vertex = pl.per_vertex;
  r.variant = pl.variant;
  r.subdivisions = pl.n;
  r.mesh = detail::refine_uniformly(pl.coarse, pl.n);
  // Coarse vertex, edge-midpoint and face-centre nodes are classified already only in the
  // per-vertex variant; classify everything else geometrically.
  classify(r.mesh, pl.poly, 1e-9 * solid.diagonal(), pl.poly.vertex.size());
  r.ok = true;
  progress.report("midpoint", 1.0);
  return r;
}

double midpoint_coarse_quality(const core::MeshDomain& solid) {
  MidpointOptions o;
  o.size = 10 * solid.diagonal();  // one subdivision: the coarse hexahedra
  const MidpointResult r = midpoint_subdivide(solid, o);
  if (!r.ok || r.mesh.num_hexes() == 0) return 1;
  const std::vector<double> sj = quality::scaled_jacobians(r.mesh);
  return *std::min_element(sj.begin(), sj.end());
}

}  // namespace vorohex::mesh
