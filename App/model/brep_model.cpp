#include "model/brep_model.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "occ/tessellate.h"

namespace vorohex::model {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Merges points closer than `tol` (hash grid of cell `tol`, probing the 27 neighbours).
class Welder {
 public:
  explicit Welder(double tol) : tol_(tol) {}
  int add(const Vec3& p, std::vector<Vec3>& points) {
    const long long ix = std::llround(std::floor(p.x() / tol_));
    const long long iy = std::llround(std::floor(p.y() / tol_));
    const long long iz = std::llround(std::floor(p.z() / tol_));
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          auto it = grid_.find(key(ix + dx, iy + dy, iz + dz));
          if (it == grid_.end()) continue;
          for (int i : it->second)
            if ((points[i] - p).norm() <= tol_) return i;
        }
    points.push_back(p);
    grid_[key(ix, iy, iz)].push_back(int(points.size()) - 1);
    return int(points.size()) - 1;
  }

 private:
  static unsigned long long key(long long x, long long y, long long z) {
    return (static_cast<unsigned long long>(x) * 73856093ULL) ^
           (static_cast<unsigned long long>(y) * 19349663ULL) ^
           (static_cast<unsigned long long>(z) * 83492791ULL);
  }
  double tol_;
  std::unordered_map<unsigned long long, std::vector<int>> grid_;
};

unsigned long long pair_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<unsigned long long>(a) << 32) | static_cast<unsigned>(b);
}

}  // namespace

std::string EntityRef::name() const {
  switch (kind) {
    case EntityKind::face:
      return "Face" + std::to_string(id);
    case EntityKind::edge:
      return "Edge" + std::to_string(id);
    case EntityKind::vertex:
      return "Vertex" + std::to_string(id);
  }
  return "?";
}

const char* convexity_name(Convexity c) {
  switch (c) {
    case Convexity::convex:
      return "convex";
    case Convexity::concave:
      return "concave";
    case Convexity::smooth:
      return "smooth";
  }
  return "?";
}

std::string ModelOptions::validate() const {
  if (!(linear_tolerance > 0 && linear_tolerance < 0.5))
    return "linear_tolerance must be in (0, 0.5) (relative to the bounding-box diagonal)";
  if (!(angular_tolerance > 0.01 && angular_tolerance < 1.6))
    return "angular_tolerance must be in (0.01, 1.6) radians";
  if (!(smooth_angle >= 0 && smooth_angle < 0.5)) return "smooth_angle must be in [0, 0.5) radians";
  return {};
}

int BRepModel::index(EntityRef e) const {
  const int nf = int(faces_.size()), ne = int(edges_.size());
  switch (e.kind) {
    case EntityKind::face:
      return e.id - 1;
    case EntityKind::edge:
      return nf + e.id - 1;
    case EntityKind::vertex:
      return nf + ne + e.id - 1;
  }
  return -1;
}

EntityRef BRepModel::entity(int i) const {
  const int nf = int(faces_.size()), ne = int(edges_.size());
  if (i < nf) return {EntityKind::face, i + 1};
  if (i < nf + ne) return {EntityKind::edge, i - nf + 1};
  return {EntityKind::vertex, i - nf - ne + 1};
}

bool BRepModel::incident(EntityRef a, EntityRef b) const {
  const auto& r = related(a);
  return std::binary_search(r.begin(), r.end(), index(b));
}

bool BRepModel::adjacent(EntityRef a, EntityRef b) const {
  if (a == b || incident(a, b)) return false;
  const auto& ra = related(a);
  const auto& rb = related(b);
  for (int x : ra)
    if (std::binary_search(rb.begin(), rb.end(), x)) return true;
  return false;
}

bool BRepModel::unconnected(EntityRef a, EntityRef b) const {
  return a != b && !incident(a, b) && !adjacent(a, b);
}

bool BRepModel::governs_interior(EntityRef e) const {
  switch (e.kind) {
    case EntityKind::face:
      return true;
    case EntityKind::edge:
      return edge(EdgeId(e.id)).convexity == Convexity::concave;
    case EntityKind::vertex:
      return vertex(VertexId(e.id)).concave;
  }
  return false;
}

BRepModel::BRepModel(const occ::Solid& solid, const ModelOptions& options) : options_(options) {
  box_ = solid.bounding_box();
  const double diag = std::max(box_.diagonal(), 1e-300);
  const int nf = solid.num_faces(), ne = solid.num_edges(), nv = solid.num_vertices();

  // Topology --------------------------------------------------------------------------
  edges_.resize(ne);
  for (int i = 1; i <= ne; ++i) {
    ModelEdge& e = edges_[i - 1];
    e.id = EdgeId(i);
    e.first = solid.edge_first_vertex(e.id);
    e.last = solid.edge_last_vertex(e.id);
    e.faces = solid.edge_faces(e.id);
    e.degenerated = solid.edge_is_degenerated(e.id);
  }
  vertices_.resize(nv);
  for (int i = 1; i <= nv; ++i) {
    vertices_[i - 1].id = VertexId(i);
    vertices_[i - 1].point = solid.vertex_point(VertexId(i));
  }
  for (const ModelEdge& e : edges_)
    for (VertexId v : {e.first, e.last})
      if (v.valid() && v.value() > 0) {
        auto& ve = vertices_[v.value() - 1].edges;
        if (std::find(ve.begin(), ve.end(), e.id) == ve.end()) ve.push_back(e.id);
      }
  faces_.resize(nf);
  for (int i = 1; i <= nf; ++i) {
    ModelFace& f = faces_[i - 1];
    f.id = FaceId(i);
    f.planar = solid.face_is_planar(f.id);
    f.wires = solid.face_wires(f.id);
    for (const auto& w : f.wires)
      for (const occ::OrientedEdge& oe : w) {
        if (std::find(f.edges.begin(), f.edges.end(), oe.edge) == f.edges.end())
          f.edges.push_back(oe.edge);
        const ModelEdge& me = edges_[oe.edge.value() - 1];
        for (VertexId v : {me.first, me.last})
          if (v.value() > 0 &&
              std::find(f.vertices.begin(), f.vertices.end(), v) == f.vertices.end())
            f.vertices.push_back(v);
      }
    for (VertexId v : f.vertices) vertices_[v.value() - 1].faces.push_back(f.id);
  }
  related_.assign(num_entities(), {});
  auto relate = [&](EntityRef a, EntityRef b) {
    related_[index(a)].push_back(index(b));
    related_[index(b)].push_back(index(a));
  };
  for (const ModelFace& f : faces_) {
    for (EdgeId e : f.edges) relate(ref(f.id), ref(e));
    for (VertexId v : f.vertices) relate(ref(f.id), ref(v));
  }
  for (const ModelEdge& e : edges_)
    for (VertexId v : {e.first, e.last})
      if (v.value() > 0) relate(ref(e.id), ref(v));
  for (auto& r : related_) {
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
  }

  // Linearisation ---------------------------------------------------------------------
  occ::TessellationOptions topt;
  topt.linear_deflection = options.linear_tolerance * diag;
  topt.angular_deflection = options.angular_tolerance;
  const occ::Tessellation tess = occ::tessellate(solid, topt);
  if (!tess.ok()) throw std::runtime_error(tess.error);

  Linearization& lin = linear_;
  Welder welder(1e-7 * diag);
  std::vector<EntityRef> origin;  // per welded point
  auto add_point = [&](const Vec3& p, EntityRef o) {
    const int i = welder.add(p, lin.points);
    if (i == int(origin.size())) origin.push_back(o);
    return i;
  };
  for (const ModelVertex& v : vertices_) add_point(v.point, ref(v.id));
  std::vector<std::vector<int>> edge_pts(ne + 1);
  std::unordered_map<unsigned long long, int> segment_edge;  // welded pair -> edge id
  for (int i = 1; i <= ne; ++i) {
    const auto& poly = tess.edge_polylines[i];
    for (const Vec3& p : poly) {
      const int k = add_point(p, ref(EdgeId(i)));
      if (edge_pts[i].empty() || edge_pts[i].back() != k) edge_pts[i].push_back(k);
    }
    for (size_t k = 1; k < edge_pts[i].size(); ++k)
      segment_edge[pair_key(edge_pts[i][k - 1], edge_pts[i][k])] = i;
  }
  for (ModelFace& f : faces_) {
    if (f.planar) {
      LinearPolygon poly;
      poly.origin = ref(f.id);
      for (const auto& w : f.wires) {
        std::vector<int> loop;
        for (const occ::OrientedEdge& oe : w) {
          std::vector<int> pts = edge_pts[oe.edge.value()];
          if (!oe.forward) std::reverse(pts.begin(), pts.end());
          for (int k : pts)
            if (loop.empty() || loop.back() != k) loop.push_back(k);
        }
        while (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();
        if (loop.size() >= 3) poly.loops.push_back(std::move(loop));
      }
      if (poly.loops.empty()) continue;
      // Newell normal of the outer loop (counter-clockwise from outside => outward).
      Vec3 n(0, 0, 0);
      const auto& L = poly.loops[0];
      for (size_t k = 0; k < L.size(); ++k)
        n += lin.points[L[k]].cross(lin.points[L[(k + 1) % L.size()]]);
      if (n.norm() <= 0) continue;
      poly.normal = n.normalized();
      f.normal = poly.normal;
      const auto& ft = tess.faces[f.id.value()];
      std::vector<int> map(ft.nodes.size());
      for (size_t k = 0; k < ft.nodes.size(); ++k) map[k] = add_point(ft.nodes[k], ref(f.id));
      for (const auto& t : ft.triangles)
        if (map[t[0]] != map[t[1]] && map[t[1]] != map[t[2]] && map[t[0]] != map[t[2]])
          poly.triangles.push_back({map[t[0]], map[t[1]], map[t[2]]});
      lin.polygons.push_back(std::move(poly));
    } else {
      const auto& ft = tess.faces[f.id.value()];
      std::vector<int> map(ft.nodes.size());
      for (size_t k = 0; k < ft.nodes.size(); ++k) map[k] = add_point(ft.nodes[k], ref(f.id));
      for (const auto& t : ft.triangles) {
        const int a = map[t[0]], b = map[t[1]], c = map[t[2]];
        if (a == b || b == c || a == c) continue;
        const Vec3 n = (lin.points[b] - lin.points[a]).cross(lin.points[c] - lin.points[a]);
        if (n.norm() <= 1e-14 * diag * diag) continue;
        lin.polygons.push_back({ref(f.id), n.normalized(), {{a, b, c}}});
      }
    }
  }

  // Segments: every polygon side once, concave if the other polygon bends outwards.
  struct Half {
    int polygon;
    Vec3 inward;  // in the polygon's plane, perpendicular to the side, into the polygon
  };
  std::unordered_map<unsigned long long, std::vector<Half>> halves;
  std::vector<std::vector<int>> neighbours(lin.points.size());
  std::vector<Vec3> pseudo(lin.points.size(), Vec3(0, 0, 0));
  std::vector<char> reflex(lin.points.size(), 0);
  for (int pi = 0; pi < int(lin.polygons.size()); ++pi) {
    const LinearPolygon& poly = lin.polygons[pi];
    for (const auto& loop : poly.loops)
      for (size_t k = 0; k < loop.size(); ++k) {
        const int a = loop[k], b = loop[(k + 1) % loop.size()], c = loop[(k + 2) % loop.size()];
        const Vec3 ab = lin.points[b] - lin.points[a], bc = lin.points[c] - lin.points[b];
        halves[pair_key(a, b)].push_back({pi, poly.normal.cross(ab).normalized()});
        neighbours[a].push_back(b);
        neighbours[b].push_back(a);
        // Corner at b: angle-weighted pseudo-normal, and whether the corner is reflex.
        const double turn = std::atan2(ab.cross(bc).dot(poly.normal), ab.dot(bc));
        pseudo[b] += (kPi - turn) * poly.normal;
        if (turn < -1e-9) reflex[b] = 1;
      }
  }
  // Any outward bend counts here: a point whose nearest boundary point is on a slightly
  // concave segment must find a governing primitive (ownership is mapped to faces later).
  const double concave_sin = 1e-9;
  for (const auto& [key, hs] : halves) {
    LinearSegment s;
    s.a = int(key >> 32);
    s.b = int(key & 0xffffffffULL);
    auto it = segment_edge.find(key);
    s.origin = it != segment_edge.end() ? ref(EdgeId(it->second))
                                        : lin.polygons[hs.front().polygon].origin;
    if (hs.size() == 2)
      s.concave = hs[0].inward.dot(lin.polygons[hs[1].polygon].normal) > concave_sin;
    lin.segments.push_back(s);
  }
  std::sort(lin.segments.begin(), lin.segments.end(),
            [](const LinearSegment& x, const LinearSegment& y) {
              return x.a != y.a ? x.a < y.a : x.b < y.b;
            });
  // Corners: concave if, seen along the inward pseudo-normal, every neighbour lies strictly
  // behind the point (then a ball can touch the boundary there alone).
  for (int i = 0; i < int(lin.points.size()); ++i) {
    LinearPoint c{i, origin[i], false};
    if (!reflex[i] && pseudo[i].norm() > 0 && !neighbours[i].empty()) {
      const Vec3 m = -pseudo[i].normalized();
      c.concave = true;
      for (int q : neighbours[i]) {
        const Vec3 d = (lin.points[q] - lin.points[i]).normalized();
        if (d.dot(m) > -concave_sin) c.concave = false;
      }
    }
    lin.corners.push_back(c);
  }
  for (const ModelVertex& v : vertices_)
    vertices_[v.id.value() - 1].concave = lin.corners[v.id.value() - 1].concave;

  // Dihedral angles from the exact face normals at the middle of each edge.
  for (ModelEdge& e : edges_) {
    const auto& pts = edge_pts[e.id.value()];
    if (e.degenerated || pts.size() < 2 || e.faces.size() != 2) continue;
    const size_t k = (pts.size() - 1) / 2;
    const Vec3 a = lin.points[pts[k]], b = lin.points[pts[k + 1]];
    const double dihedral = solid.interior_angle(e.id, 0.5 * (a + b), (b - a).normalized());
    if (std::isnan(dihedral)) continue;  // a seam
    e.dihedral = dihedral;
    if (std::abs(e.dihedral - kPi) < options.smooth_angle)
      e.convexity = Convexity::smooth;
    else
      e.convexity = e.dihedral > kPi ? Convexity::concave : Convexity::convex;
  }
}

ModelResult build_model(const occ::Solid& solid, const ModelOptions& options) {
  ModelResult result;
  if (std::string why = options.validate(); !why.empty()) {
    result.diagnostics.push_back(core::make_error("invalid_options", why));
    return result;
  }
  try {
    result.model = std::make_unique<BRepModel>(solid, options);
  } catch (const std::exception& e) {
    result.diagnostics.push_back(core::make_error("model_failed", e.what()));
  }
  return result;
}

}  // namespace vorohex::model
