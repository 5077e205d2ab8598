#include "mesh/tet_split.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "core/isolated_call.h"
#include "core/option_checks.h"
#include "mesh/detail/boundary_labels.h"
#include "mesh/detail/cgal_tets.h"
#include "mesh/detail/tet_to_hex.h"
#include "occ/tessellate.h"

namespace vorohex::mesh {

void TetSplitOptions::validate() const {
  core::require_positive("TetSplitOptions.size", size);
  core::require_at_least("TetSplitOptions.max_hexes", static_cast<long long>(max_hexes), 1);
}

namespace {

using core::NodeClass;
using core::Vec3;
using detail::boundary_labels;
using detail::BoundaryLabels;
using detail::facet_of;

// The boundary triangulation as one closed surface, each triangle's patch the model face
// it approximates (nodes shared between faces are merged: tessellate() shares them).
detail::TetSurface merge(const occ::Tessellation& t) {
  detail::TetSurface s;
  std::map<std::tuple<double, double, double>, int> index;
  for (const occ::FaceTriangulation& f : t.faces) {
    if (!f.face.valid() || f.face.value() == 0) continue;
    std::vector<int> local(f.nodes.size());
    for (std::size_t i = 0; i < f.nodes.size(); ++i) {
      const Vec3& p = f.nodes[i];
      auto [it, added] =
          index.emplace(std::make_tuple(p.x(), p.y(), p.z()), static_cast<int>(s.points.size()));
      if (added) s.points.push_back(p);
      local[i] = it->second;
    }
    for (const auto& tri : f.triangles) {
      const std::array<int, 3> g{local[tri[0]], local[tri[1]], local[tri[2]]};
      if (g[0] == g[1] || g[1] == g[2] || g[0] == g[2]) continue;  // collapsed by merging
      s.triangles.push_back(g);
      s.patch.push_back(f.face.value());
    }
  }
  return s;
}

// Where the merged boundary triangulation is open: model faces OCCT left without triangles
// and model edges along which the triangles of the two sides do not meet (e.g. next to an
// edge much shorter than the triangles). Empty when it is closed.
std::string open_boundary(const occ::Tessellation& t, const detail::TetSurface& s) {
  std::map<std::tuple<double, double, double>, int> index;
  for (std::size_t i = 0; i < s.points.size(); ++i)
    index.emplace(std::make_tuple(s.points[i].x(), s.points[i].y(), s.points[i].z()),
                  static_cast<int>(i));
  std::map<std::pair<int, int>, int> uses;
  for (const auto& tri : s.triangles)
    for (int j = 0; j < 3; ++j)
      ++uses[{std::min(tri[j], tri[(j + 1) % 3]), std::max(tri[j], tri[(j + 1) % 3])}];
  std::vector<std::string> names;
  for (std::size_t f = 1; f < t.faces.size(); ++f)
    if (t.faces[f].face.valid() && t.faces[f].triangles.empty())
      names.push_back(core::entity_name(core::FaceId(static_cast<int>(f))) + " (no triangles)");
  for (std::size_t e = 1; e < t.edge_polylines.size(); ++e) {
    const auto& pl = t.edge_polylines[e];
    for (std::size_t k = 0; k + 1 < pl.size(); ++k) {
      const auto a = index.find(std::make_tuple(pl[k].x(), pl[k].y(), pl[k].z()));
      const auto b = index.find(std::make_tuple(pl[k + 1].x(), pl[k + 1].y(), pl[k + 1].z()));
      if (a == index.end() || b == index.end() || a->second == b->second) continue;
      const auto it = uses.find({std::min(a->second, b->second), std::max(a->second, b->second)});
      if (it == uses.end() || it->second != 2) {
        names.push_back(core::entity_name(core::EdgeId(static_cast<int>(e))));
        break;
      }
    }
  }
  bool open = !names.empty();
  for (const auto& [edge, n] : uses) open |= n != 2;
  if (!open) return "";
  std::string list;
  for (std::size_t i = 0; i < names.size() && i < 8; ++i) list += (i ? ", " : "") + names[i];
  if (names.size() > 8) list += ", ...";
  return "the boundary triangulation is not closed" +
         (names.empty() ? std::string() : " (at " + list + ")");
}

using FacetFaces = std::map<std::array<int, 3>, int>;
using EdgeFaces = std::map<std::array<int, 2>, int>;
using EdgeSet = std::set<std::array<int, 2>>;

// Two boundary facets k1, k2 of a tet on one model face, sharing an edge (the crease):
// the split puts a hex corner at the crease's midpoint, framed by an end of the crease and
// the two facets' centroids. Placing those nodes on the curved face bends the crease open;
// true when that frame's determinant falls below a quarter of its straight value (or flips):
// the hex then inverts there, and no move on the face undoes it (HexMe i14: facets 61
// degrees apart on a cylinder, i17: 41).
bool crease_flattens(const std::array<int, 3>& k1, const std::array<int, 3>& k2,
                     const std::vector<Vec3>& points, const occ::Solid& solid, int face) {
  std::vector<int> shared, other;
  for (int v : k1) (std::find(k2.begin(), k2.end(), v) != k2.end() ? shared : other).push_back(v);
  for (int v : k2)
    if (std::find(k1.begin(), k1.end(), v) == k1.end()) other.push_back(v);
  if (shared.size() != 2 || other.size() != 2) return false;
  const Vec3 &a = points[shared[0]], &b = points[shared[1]];
  const Vec3 m = 0.5 * (a + b), g1 = (a + b + points[other[0]]) / 3.0,
             g2 = (a + b + points[other[1]]) / 3.0;
  auto on = [&](const Vec3& p) { return solid.project_to_face(core::FaceId(face), p); };
  const Vec3 m1 = on(m), h1 = on(g1), h2 = on(g2);
  if (!m1.allFinite() || !h1.allFinite() || !h2.allFinite()) return false;
  for (const Vec3* end : {&a, &b}) {
    const double straight = (*end - m).dot((g1 - m).cross(g2 - m));
    const double placed = (on(*end) - m1).dot((h1 - m1).cross(h2 - m1));
    if (straight != 0 && placed / straight < 0.25) return true;
  }
  return false;
}

// Leaves out tetrahedra lying flat on the boundary: two or three of their faces are
// boundary faces whose outward normals agree within 40 degrees (on one curved model face,
// or on two faces meeting smoothly, as fillets do). The boundary triangles there are coarse
// next to the curvature, and moving their nodes onto the CAD would flatten and invert
// them. A tet across a sharp model edge (normals far apart) stays. So does one with two
// faces on one model face further apart, unless crease_flattens() says its split inverts
// on the CAD. Its other faces become boundary faces (of the same model face when there was
// one), unless that would pinch the boundary (an edge in more than two boundary faces).
std::size_t remove_caps(std::vector<std::array<int, 4>>& tets, const std::vector<Vec3>& points,
                        const occ::Solid& solid, FacetFaces& facet_face, EdgeFaces& edge_face) {
  std::map<std::array<int, 3>, int> count;
  for (const auto& t : tets)
    for (int j = 0; j < 4; ++j) ++count[facet_of(t, j)];
  // Boundary facets per edge: a removal must not leave an edge in more than two (the
  // boundary would pinch there, not close).
  std::map<std::array<int, 2>, int> boundary_at;
  auto edges_of = [](const std::array<int, 3>& k) {
    return std::array<std::array<int, 2>, 3>{{{k[0], k[1]}, {k[1], k[2]}, {k[0], k[2]}}};
  };
  for (const auto& [k, n] : count)
    if (n == 1)
      for (const auto& e : edges_of(k)) ++boundary_at[e];
  const double flat = std::cos(40.0 * M_PI / 180.0);
  std::vector<std::array<int, 4>> kept;
  std::size_t removed = 0;
  for (const auto& t : tets) {
    int on_boundary = 0, face = 0;
    bool same_face = true;
    std::array<Vec3, 4> normal;  // outward, per boundary facet
    std::array<std::array<int, 3>, 4> facets;
    for (int j = 0; j < 4; ++j) {
      const std::array<int, 3> k = facet_of(t, j);
      if (count[k] != 1) continue;
      facets[on_boundary] = k;
      Vec3 n = (points[k[1]] - points[k[0]]).cross(points[k[2]] - points[k[0]]);
      if (n.dot(points[t[j]] - points[k[0]]) > 0) n = -n;
      const double len = n.norm();
      normal[on_boundary++] = len > 0 ? Vec3(n / len) : Vec3::Zero();
      const auto it = facet_face.find(k);
      const int f = it == facet_face.end() ? 0 : it->second;
      if (f == 0 || (face != 0 && f != face)) same_face = false;
      face = f;
    }
    if (!same_face) face = 0;
    bool smooth = true;
    for (int a = 0; a < on_boundary; ++a)
      for (int b = a + 1; b < on_boundary; ++b) smooth &= normal[a].dot(normal[b]) > flat;
    const bool crease = !smooth && on_boundary == 2 && face != 0 && normal[0].dot(normal[1]) > 0 &&
                        crease_flattens(facets[0], facets[1], points, solid, face);
    const bool lies_flat = on_boundary >= 2 && on_boundary <= 3 && (smooth || crease);
    bool pinches = false;
    if (lies_flat) {
      std::map<std::array<int, 2>, int> after;
      for (int j = 0; j < 4; ++j) {
        const std::array<int, 3> k = facet_of(t, j);
        for (const auto& e : edges_of(k)) {
          if (!after.count(e)) after[e] = boundary_at[e];
          after[e] += count[k] == 1 ? -1 : 1;
        }
      }
      for (const auto& [e, n] : after) pinches |= n > 2;
    }
    if (!lies_flat || pinches) {
      kept.push_back(t);
      continue;
    }
    ++removed;
    for (int j = 0; j < 4; ++j) {
      const std::array<int, 3> k = facet_of(t, j);
      for (const auto& e : edges_of(k)) boundary_at[e] += count[k] == 1 ? -1 : 1;
      if (count[k] == 1) {
        --count[k];
        continue;
      }
      --count[k];
      if (face == 0) continue;  // exposed on two model faces: the nearest one takes it
      facet_face[k] = face;     // exposed: now on the model face
      edge_face[{k[0], k[1]}] = edge_face[{k[1], k[2]}] = edge_face[{k[0], k[2]}] = face;
    }
  }
  tets.swap(kept);
  return removed;
}

// Moves boundary nodes onto the CAD and places the others as on quadratic (P2)
// tetrahedra whose edge midpoints are the moved ones: corners to the nearest model
// vertex, feature nodes to the nearest model edge, other boundary nodes onto the model
// face of their boundary triangle; face and cell centroids follow the curved edges (a
// face centroid is -1/9 of its corners plus 4/9 of its edge midpoints, a cell centroid
// -1/8 and 1/4), so interior nodes keep their place relative to a curved boundary.
void place_on_cad(core::HexMesh& m, const occ::Solid& solid,
                  const std::vector<std::array<int, 4>>& tets, const detail::TetSplitNodes& split,
                  const std::vector<int>& dimension, const std::vector<int>& node_face,
                  const EdgeSet& features, const FacetFaces& facet_face,
                  const EdgeFaces& edge_face) {
  std::map<std::array<int, 4>, int> quads;
  for (const core::HexNodes& h : m.hexes())
    for (const auto& f : core::kHexFaces) {
      std::array<int, 4> k{h[f[0]], h[f[1]], h[f[2]], h[f[3]]};
      std::sort(k.begin(), k.end());
      ++quads[k];
    }
  std::vector<char> boundary(m.num_nodes(), 0);
  for (const auto& [k, n] : quads)
    if (n == 1)
      for (int v : k) boundary[v] = 1;

  std::map<std::array<int, 2>, int> midpoint;
  std::vector<int> tet_centroid;
  for (std::size_t i = 0; i < split.origin.size(); ++i) {
    const auto& o = split.origin[i];
    const int node = static_cast<int>(split.first_new + i);
    if (o[0] < 0)
      tet_centroid.push_back(node);
    else if (o[2] < 0)
      midpoint[{o[0], o[1]}] = node;
  }
  auto pt = [&](int n) { return m.point(core::NodeId(n)); };
  auto mid = [&](int a, int b) { return pt(midpoint.at({std::min(a, b), std::max(a, b)})); };
  auto put = [&](int i, const Vec3& p, int dim, int face) {
    const core::NodeId id(i);
    if (dim == 0) {
      core::VertexId best(1);
      for (core::VertexId v : solid.vertices())
        if (solid.distance_to_vertex(v, p) < solid.distance_to_vertex(best, p)) best = v;
      m.set_point(id, solid.vertex_point(best));
      m.set_node_class(id, NodeClass::on(best));
    } else if (dim == 1) {
      const core::EdgeId e = solid.nearest_edge(p);
      m.set_point(id, solid.project_to_edge(e, p));
      m.set_node_class(id, NodeClass::on(e));
    } else {
      const core::FaceId f = face > 0 ? core::FaceId(face) : solid.nearest_face(p);
      m.set_point(id, solid.project_to_face(f, p));
      m.set_node_class(id, NodeClass::on(f));
    }
  };
  // Corners and edge midpoints first: the centroids are placed from them.
  for (std::size_t i = 0; i < m.num_nodes(); ++i) {
    if (!boundary[i]) continue;
    if (i < split.first_new) {
      put(static_cast<int>(i), pt(static_cast<int>(i)), std::min(dimension[i], 2), node_face[i]);
      continue;
    }
    const auto& o = split.origin[i - split.first_new];
    if (o[0] < 0 || o[2] >= 0) continue;
    const auto it = edge_face.find({o[0], o[1]});
    put(static_cast<int>(i), pt(static_cast<int>(i)), features.count({o[0], o[1]}) ? 1 : 2,
        it == edge_face.end() ? 0 : it->second);
  }
  for (std::size_t i = 0; i < split.origin.size(); ++i) {
    const auto& o = split.origin[i];
    if (o[2] < 0) continue;
    const int node = static_cast<int>(split.first_new + i);
    const Vec3 p = -(pt(o[0]) + pt(o[1]) + pt(o[2])) / 9.0 +
                   4.0 / 9.0 * (mid(o[0], o[1]) + mid(o[1], o[2]) + mid(o[0], o[2]));
    if (!boundary[node]) {
      m.set_point(core::NodeId(node), p);
      continue;
    }
    const auto it = facet_face.find(o);
    put(node, p, 2, it == facet_face.end() ? 0 : it->second);
  }
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const auto& v = tets[t];
    Vec3 corners = Vec3::Zero(), mids = Vec3::Zero();
    for (int i = 0; i < 4; ++i) {
      corners += pt(v[i]);
      for (int j = i + 1; j < 4; ++j) mids += mid(v[i], v[j]);
    }
    m.set_point(core::NodeId(tet_centroid[t]), -corners / 8.0 + mids / 4.0);
  }
}

}  // namespace

TetSplitResult tet_split(const occ::Solid& solid, const TetSplitOptions& options,
                         const core::Progress& progress) {
  options.validate();
  TetSplitResult r;
  auto fail = [&](const std::string& message) {
    r.diagnostics.push_back(
        core::make_error("tet_split_failed", "The tetrahedral fallback failed: " + message + "."));
    return std::move(r);
  };
  progress.report("tetrahedra", 0.0);
  // A split halves the edges; a size coarser than the solid still gets a few tetrahedra
  // across it (Delaunay refinement needs them to see the volume at all).
  const double tet_size = std::min(2 * options.size, solid.diagonal() / 6);
  if (tet_size < 2 * options.size) {
    std::ostringstream s;
    s << "The size " << options.size << " is coarse for this solid; the fallback used "
      << tet_size / 2 << " (a sixth of the diagonal per tetrahedron).";
    r.diagnostics.push_back(core::make_info("size_reduced", s.str()));
  }
  occ::TessellationOptions topt;
  topt.linear_deflection = std::min(0.05 * tet_size, 0.01 * solid.diagonal());
  const occ::Tessellation tess = occ::tessellate(solid, topt);
  if (!tess.ok()) return fail(tess.error);
  detail::TetRequest request;
  request.surface = merge(tess);
  if (const std::string open = open_boundary(tess, request.surface); !open.empty())
    return fail(open);
  request.size = tet_size;
  // Every model edge is a feature the tetrahedra keep (their polylines share the nodes).
  for (std::size_t e = 1; e < tess.edge_polylines.size(); ++e)
    if (tess.edge_polylines[e].size() >= 2) request.features.push_back(tess.edge_polylines[e]);

  // CGAL runs in a child process: its ODT optimiser (CGAL 5.5) can remove a vertex that a
  // moved protecting ball hides and crash (HexMe i09); a crash then costs one retry with
  // the perturber only, not the caller's process. Cancelling kills the child.
  detail::Tetrahedra tm;
  core::IsolatedCallOptions iso;
  iso.stage = "tetrahedra";
  for (const detail::TetOptimiser opt :
       {detail::TetOptimiser::odt, detail::TetOptimiser::perturb}) {
    request.optimiser = opt;
    const core::IsolatedResult run = core::isolated_call(
        [&request] { return detail::to_bytes(detail::mesh_tetrahedra(request)); }, progress, iso);
    if (run.status == core::IsolatedResult::Status::cancelled) {
      r.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
      return r;
    }
    if (run.status == core::IsolatedResult::Status::failed) return fail(run.message);
    if (run.ok()) {
      if (!detail::from_bytes(run.data, tm)) return fail("the tetrahedral mesh came back damaged");
      break;
    }
    if (opt == detail::TetOptimiser::perturb)
      return fail("CGAL's tetrahedral mesher crashed twice (" + run.message + ")");
    r.diagnostics.push_back(core::make_warning(
        "tet_optimiser_crashed",
        "CGAL's tetrahedral mesher crashed while optimising the tetrahedra (" + run.message +
            "); meshed again with sliver perturbation only (poorer tetrahedra)."));
  }
  progress.report("tetrahedra", 0.6);
  if (progress.cancelled()) {
    r.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
    return r;
  }
  r.tetrahedra = tm.tets.size();
  if (r.tetrahedra == 0) return fail("no tetrahedron was generated");
  if (4 * r.tetrahedra > options.max_hexes) {
    std::ostringstream s;
    s << "the split would give " << 4 * r.tetrahedra
      << " hexahedra, more than max_hexes = " << options.max_hexes;
    r.diagnostics.push_back(core::make_error("too_many_hexes", s.str()));
    return r;
  }

  if (tm.filled > 0)
    r.diagnostics.push_back(core::make_info(
        "pinches_filled", std::to_string(tm.filled) +
                              " tetrahedra CGAL had left out between two fans of tetrahedra "
                              "around one edge were put back (their centroids lie inside the "
                              "solid), so that the boundary is a closed surface there."));
  for (const Vec3& p : tm.points) r.mesh.add_node(p);
  const std::vector<int>& dimension = tm.dimension;
  std::vector<std::array<int, 4>> tets = std::move(tm.tets);
  const EdgeSet feature_edges(tm.feature_edges.begin(), tm.feature_edges.end());
  // The model face of every boundary facet of the tetrahedra, and through them of their
  // boundary edges and nodes.
  BoundaryLabels labels = boundary_labels(tets, tm.points, tm.facets, tm.facet_patch, solid);
  FacetFaces& facet_face = labels.facet_face;
  EdgeFaces& edge_face = labels.edge_face;
  const std::vector<int>& node_face = labels.node_face;
  // Until none is left: leaving one out can expose a neighbour that is a cap in turn.
  std::size_t caps = 0;
  for (std::size_t removed = 1; removed > 0;) {
    removed = remove_caps(tets, tm.points, solid, facet_face, edge_face);
    caps += removed;
  }
  if (caps > 0)
    r.diagnostics.push_back(core::make_info(
        "caps_removed", std::to_string(caps) +
                            " tetrahedra lying flat on the boundary (two or three of their "
                            "faces on it, with outward normals within 40 degrees, or two on "
                            "one curved face whose crease the CAD bends open) were left "
                            "out; the surface is followed by their neighbours."));
  r.tetrahedra = tets.size();
  const detail::TetSplitNodes split = detail::split_tetrahedra(r.mesh, tets);
  progress.report("tetrahedra", 0.8);
  place_on_cad(r.mesh, solid, tets, split, dimension, node_face, feature_edges, facet_face,
               edge_face);
  r.ok = true;
  progress.report("tetrahedra", 1.0);
  return r;
}

}  // namespace vorohex::mesh
