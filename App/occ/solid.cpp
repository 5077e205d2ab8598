#include "occ/solid.h"

#include <BRepAdaptor_Curve.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <ElSLib.hxx>
#include <GCPnts_AbscissaPoint.hxx>
#include <GProp_GProps.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomAdaptor_Curve.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <GeomLib_IsPlanarSurface.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Lin.hxx>
#include <gp_Pnt2d.hxx>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "occ/detail/face_classifier.h"
#include "occ/face_chart.h"
#include "occ/solid_impl.h"

namespace vorohex::occ {
namespace {

gp_Pnt to_pnt(const Vec3& p) {
  return gp_Pnt(p.x(), p.y(), p.z());
}
Vec3 to_vec(const gp_Pnt& p) {
  return Vec3(p.X(), p.Y(), p.Z());
}

// Distance from a point to a (possibly void) box; 0 inside.
double box_distance(const Bnd_Box& box, const Vec3& p) {
  if (box.IsVoid()) return 0.0;
  double x0, y0, z0, x1, y1, z1;
  box.Get(x0, y0, z0, x1, y1, z1);
  const double dx = std::max({x0 - p.x(), 0.0, p.x() - x1});
  const double dy = std::max({y0 - p.y(), 0.0, p.y() - y1});
  const double dz = std::max({z0 - p.z(), 0.0, p.z() - z1});
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// Closest point on the segment [a, b].
Vec3 closest_on_segment(const Vec3& a, const Vec3& b, const Vec3& p) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 <= 0.0) return a;
  const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return a + t * ab;
}

void check_id(int value, int count, const char* what) {
  if (value < 1 || value > count)
    throw std::out_of_range(std::string(what) + " id " + std::to_string(value) +
                            " is out of range 1.." + std::to_string(count));
}

}  // namespace

std::unique_ptr<Solid::Impl> make_solid_impl(const TopoDS_Shape& solid) {
  auto impl = std::make_unique<Solid::Impl>();
  impl->solid = solid;
  TopExp::MapShapes(solid, TopAbs_FACE, impl->faces);
  TopExp::MapShapes(solid, TopAbs_EDGE, impl->edges);
  TopExp::MapShapes(solid, TopAbs_VERTEX, impl->vertices);
  for (TopExp_Explorer ex(solid, TopAbs_SOLID); ex.More(); ex.Next())
    impl->parts.push_back(TopoDS::Solid(ex.Current()));
  impl->interface_face.assign(impl->faces.Extent() + 1, 0);
  if (impl->parts.size() > 1) {
    std::vector<int> uses(impl->faces.Extent() + 1, 0);
    for (const TopoDS_Solid& part : impl->parts) {
      TopTools_IndexedMapOfShape part_faces;
      TopExp::MapShapes(part, TopAbs_FACE, part_faces);
      for (int i = 1; i <= part_faces.Extent(); ++i) ++uses[impl->faces.FindIndex(part_faces(i))];
    }
    for (std::size_t f = 1; f < uses.size(); ++f) impl->interface_face[f] = uses[f] > 1;
  }

  const int nf = impl->faces.Extent(), ne = impl->edges.Extent();
  auto edge_faces = std::make_shared<std::vector<std::vector<int>>>(ne + 1);
  auto edges = std::make_shared<std::vector<EdgeCache>>(ne + 1);
  auto faces = std::make_shared<std::vector<FaceCache>>(nf + 1);

  for (int i = 1; i <= ne; ++i) {
    const TopoDS_Edge& e = TopoDS::Edge(impl->edges(i));
    EdgeCache& c = (*edges)[i];
    // First/last in the edge's parametric direction (vertex orientations inside the edge,
    // ignoring the orientation the edge has in the solid): see solid.h and face_wires.
    const TopoDS_Vertex v0 = TopExp::FirstVertex(e, false), v1 = TopExp::LastVertex(e, false);
    c.v_first = v0.IsNull() ? 0 : impl->vertices.FindIndex(v0);
    c.v_last = v1.IsNull() ? 0 : impl->vertices.FindIndex(v1);
    if (!v0.IsNull()) c.p_first = BRep_Tool::Pnt(v0);
    if (!v1.IsNull()) c.p_last = BRep_Tool::Pnt(v1);
    if (!BRep_Tool::Degenerated(e)) {
      c.curve = BRep_Tool::Curve(e, c.first, c.last);
      if (!c.curve.IsNull()) {
        GeomAdaptor_Curve ac(c.curve, c.first, c.last);
        c.line = ac.GetType() == GeomAbs_Line;
      }
      BRepBndLib::Add(e, c.box, false);
    }
  }

  for (int i = 1; i <= nf; ++i) {
    const TopoDS_Face& f = TopoDS::Face(impl->faces(i));
    FaceCache& c = (*faces)[i];
    c.reversed = f.Orientation() == TopAbs_REVERSED;
    c.surface = BRep_Tool::Surface(f);
    c.tolerance = BRep_Tool::Tolerance(f);
    BRepTools::UVBounds(f, c.umin, c.umax, c.vmin, c.vmax);
    GeomAdaptor_Surface as(c.surface);
    c.is_plane = as.GetType() == GeomAbs_Plane;
    if (c.is_plane) c.plane = as.Plane();
    c.planar = c.is_plane || GeomLib_IsPlanarSurface(c.surface, 1e-7).IsPlanar();
    BRepBndLib::AddOptimal(f, c.box, false, false);
    c.classifier = std::make_shared<const detail::FaceClassifier>(f, std::max(c.tolerance, 1e-9));
    for (TopExp_Explorer ex(f, TopAbs_EDGE); ex.More(); ex.Next()) {
      const int e = impl->edges.FindIndex(ex.Current());
      if (std::find(c.edges.begin(), c.edges.end(), e) == c.edges.end()) c.edges.push_back(e);
      auto& ef = (*edge_faces)[e];
      if (std::find(ef.begin(), ef.end(), i) == ef.end()) ef.push_back(i);
    }
  }
  impl->face_cache = faces;
  impl->edge_cache = edges;
  impl->edge_faces = edge_faces;
  return impl;
}

Solid::Solid(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {
  if (!impl_) throw std::invalid_argument("occ::Solid needs a shape");
}
Solid::Solid(Solid&&) noexcept = default;
Solid& Solid::operator=(Solid&&) noexcept = default;
Solid::~Solid() = default;

Solid Solid::clone() const {
  return Solid(std::make_unique<Impl>(*impl_));
}

int Solid::num_faces() const {
  return impl_->faces.Extent();
}
int Solid::num_edges() const {
  return impl_->edges.Extent();
}
int Solid::num_vertices() const {
  return impl_->vertices.Extent();
}

// The face in the map carries its orientation in the solid, and exploring it composes
// orientations down to the edges. OCCT's convention is that the material of an oriented
// face lies to the left of its composed-oriented edges seen against the oriented normal,
// and the oriented normal of a face of a valid solid points outwards: so an edge whose
// composed orientation is FORWARD is traversed from edge_first_vertex to edge_last_vertex
// (its parametric direction) with the material on the left seen from outside.
std::vector<std::vector<OrientedEdge>> Solid::face_wires(FaceId f) const {
  check_id(f.value(), num_faces(), "face");
  std::vector<std::vector<OrientedEdge>> result;
  try {
    const TopoDS_Face& face = TopoDS::Face(impl_->faces(f.value()));
    const TopoDS_Wire outer = BRepTools::OuterWire(face);
    std::vector<TopoDS_Wire> wires;
    if (!outer.IsNull()) wires.push_back(outer);
    for (TopExp_Explorer ex(face, TopAbs_WIRE); ex.More(); ex.Next())
      if (outer.IsNull() || !ex.Current().IsSame(outer))
        wires.push_back(TopoDS::Wire(ex.Current()));
    for (const TopoDS_Wire& w : wires) {
      std::vector<OrientedEdge> loop;
      for (BRepTools_WireExplorer wex(w, face); wex.More(); wex.Next()) {
        const TopoDS_Edge& e = wex.Current();
        loop.push_back({EdgeId(impl_->edges.FindIndex(e)), e.Orientation() != TopAbs_REVERSED});
      }
      result.push_back(std::move(loop));
    }
  } catch (const Standard_Failure& e) {
    throw std::runtime_error(std::string("cannot explore the wires of Face") +
                             std::to_string(f.value()) + ": " + e.GetMessageString());
  }
  return result;
}

std::vector<FaceId> Solid::edge_faces(EdgeId e) const {
  check_id(e.value(), num_edges(), "edge");
  std::vector<FaceId> ids;
  for (int f : (*impl_->edge_faces)[e.value()]) ids.emplace_back(f);
  return ids;
}

VertexId Solid::edge_first_vertex(EdgeId e) const {
  check_id(e.value(), num_edges(), "edge");
  return VertexId(impl_->edge(e.value()).v_first);
}
VertexId Solid::edge_last_vertex(EdgeId e) const {
  check_id(e.value(), num_edges(), "edge");
  return VertexId(impl_->edge(e.value()).v_last);
}
bool Solid::edge_is_degenerated(EdgeId e) const {
  check_id(e.value(), num_edges(), "edge");
  return BRep_Tool::Degenerated(TopoDS::Edge(impl_->edges(e.value())));
}

int Solid::num_solids() const {
  return static_cast<int>(impl_->parts.size());
}

Solid Solid::part(int k) const {
  if (k < 0 || k >= num_solids())
    throw std::out_of_range("solid " + std::to_string(k) + " out of range (" +
                            std::to_string(num_solids()) + " solids)");
  return make_solid(impl_->parts[k]);
}

std::vector<int> Solid::part_ids(const Solid& part, int dim) const {
  if (dim < 0 || dim > 2) throw std::invalid_argument("part_ids: dim must be 0, 1 or 2");
  const TopTools_IndexedMapOfShape& from = dim == 0   ? part.impl().vertices
                                           : dim == 1 ? part.impl().edges
                                                      : part.impl().faces;
  const TopTools_IndexedMapOfShape& to = dim == 0   ? impl_->vertices
                                         : dim == 1 ? impl_->edges
                                                    : impl_->faces;
  std::vector<int> ids(from.Extent() + 1, 0);
  for (int i = 1; i <= from.Extent(); ++i) ids[i] = to.FindIndex(from(i));
  return ids;
}

bool Solid::face_is_interface(FaceId f) const {
  check_id(f.value(), num_faces(), "face");
  return impl_->interface_face[f.value()] != 0;
}

int Solid::num_interface_faces() const {
  return static_cast<int>(
      std::count(impl_->interface_face.begin(), impl_->interface_face.end(), char(1)));
}

double Solid::volume() const {
  // Adaptive integration to a relative error of about 1e-11: the fixed-order default is
  // exact on planes but errs by 1e-7 on cylinders, which the decomposition's volume check
  // (1e-9) would read as a gap between its pieces.
  // Computed once per shape (clones share it).
  std::call_once(impl_->volume->once, [&] {
    GProp_GProps props;
    BRepGProp::VolumeProperties(impl_->solid, props, 1e-11);
    impl_->volume->value = props.Mass();
  });
  return impl_->volume->value;
}

double Solid::area(FaceId f) const {
  check_id(f.value(), num_faces(), "face");
  GProp_GProps props;
  BRepGProp::SurfaceProperties(impl_->faces(f.value()), props);
  return props.Mass();
}

namespace {
BoundingBox to_box(const Bnd_Box& box) {
  BoundingBox b;
  if (box.IsVoid()) return b;
  double x0, y0, z0, x1, y1, z1;
  box.Get(x0, y0, z0, x1, y1, z1);
  b.min = Vec3(x0, y0, z0);
  b.max = Vec3(x1, y1, z1);
  return b;
}
}  // namespace

BoundingBox Solid::bounding_box() const {
  // The union of the faces' boxes, made when the solid was (the same optimal boxes OCCT's
  // BRepBndLib::AddOptimal of the whole solid joins): computed again on every call, the
  // solid's box took 20 of the 37 s HexMe i08's decomposition spent (its pieces' B-spline
  // blades, a particle swarm per surface, and callers that ask for the diagonal often).
  Bnd_Box box;
  for (int i = 1; i <= impl_->faces.Extent(); ++i) box.Add(impl_->face(i).box);
  return to_box(box);
}

BoundingBox Solid::face_bounding_box(FaceId f) const {
  check_id(f.value(), num_faces(), "face");
  return to_box(impl_->face(f.value()).box);
}

BoundingBox Solid::edge_bounding_box(EdgeId e) const {
  check_id(e.value(), num_edges(), "edge");
  return to_box(impl_->edge(e.value()).box);
}

bool Solid::face_is_planar(FaceId f) const {
  check_id(f.value(), num_faces(), "face");
  return impl_->face(f.value()).planar;
}

Vec3 Solid::vertex_point(VertexId v) const {
  check_id(v.value(), num_vertices(), "vertex");
  return to_vec(BRep_Tool::Pnt(TopoDS::Vertex(impl_->vertices(v.value()))));
}

double Solid::edge_length(EdgeId e) const {
  check_id(e.value(), num_edges(), "edge");
  const EdgeCache& c = impl_->edge(e.value());
  if (c.curve.IsNull()) return 0.0;
  if (c.line) return c.p_first.Distance(c.p_last);
  GeomAdaptor_Curve ac(c.curve, c.first, c.last);
  return GCPnts_AbscissaPoint::Length(ac, c.first, c.last);
}

std::vector<Vec3> Solid::edge_points_by_length(EdgeId e, int n) const {
  check_id(e.value(), num_edges(), "edge");
  if (n < 1)
    throw std::invalid_argument("edge_points_by_length needs n >= 1, got " + std::to_string(n));
  const EdgeCache& c = impl_->edge(e.value());
  const Vec3 a = to_vec(c.p_first), b = to_vec(c.p_last);
  std::vector<Vec3> pts(n + 1);
  pts[0] = a;
  pts[n] = b;
  if (c.curve.IsNull()) {
    for (int i = 1; i < n; ++i) pts[i] = a;
    return pts;
  }
  if (c.line) {
    for (int i = 1; i < n; ++i) pts[i] = a + (b - a) * (double(i) / n);
    return pts;
  }
  try {
    GeomAdaptor_Curve ac(c.curve, c.first, c.last);
    const double length = GCPnts_AbscissaPoint::Length(ac, c.first, c.last);
    const double tol = std::max(1e-12, 1e-10 * length);
    double u = c.first;
    for (int i = 1; i < n; ++i) {
      // Step from the previous parameter (shorter integrals), by the exact remaining share.
      GCPnts_AbscissaPoint ap(tol, ac, length / n, u);
      if (!ap.IsDone()) throw std::runtime_error("abscissa point failed");
      u = ap.Parameter();
      pts[i] = to_vec(ac.Value(u));
    }
  } catch (const Standard_Failure& ex) {
    throw std::runtime_error("cannot divide Edge" + std::to_string(e.value()) + ": " +
                             ex.GetMessageString());
  }
  return pts;
}

Vec3 Solid::project_to_edge(EdgeId e, const Vec3& p) const {
  check_id(e.value(), num_edges(), "edge");
  const EdgeCache& c = impl_->edge(e.value());
  const Vec3 a = to_vec(c.p_first), b = to_vec(c.p_last);
  if (c.curve.IsNull()) return a;
  if (c.line) return closest_on_segment(a, b, p);
  Vec3 best = (p - a).squaredNorm() <= (p - b).squaredNorm() ? a : b;
  double best_d = (p - best).norm();
  try {
    GeomAPI_ProjectPointOnCurve proj(to_pnt(p), c.curve, c.first, c.last);
    for (int i = 1; i <= proj.NbPoints(); ++i) {
      const double d = proj.Distance(i);
      if (d < best_d) {
        best_d = d;
        best = to_vec(proj.Point(i));
      }
    }
  } catch (const Standard_Failure&) {
    // keep the nearer end point
  }
  return best;
}

namespace {

// A surface projector per face and thread, initialised once: OCCT's point-on-surface
// extremum samples the surface on a grid when initialised, which dominates a projection
// (smoothing projects every boundary node many times). Keyed by the surface and the
// face's parameter bounds; the handle keeps the surface alive, so a key is never reused.
GeomAPI_ProjectPointOnSurf& projector(const FaceCache& c) {
  struct Entry {
    Handle(Geom_Surface) surface;
    std::unique_ptr<GeomAPI_ProjectPointOnSurf> projector;
  };
  using Key = std::tuple<const Geom_Surface*, double, double, double, double>;
  thread_local std::map<Key, Entry> cache;
  const Key key{c.surface.get(), c.umin, c.umax, c.vmin, c.vmax};
  auto it = cache.find(key);
  if (it == cache.end()) {
    if (cache.size() >= 4096) cache.clear();  // bounded: solids come and go
    auto proj = std::make_unique<GeomAPI_ProjectPointOnSurf>();
    proj->Init(c.surface, c.umin, c.umax, c.vmin, c.vmax, Extrema_ExtAlgo_Tree);
    // Minima only: a maximum of the distance is never a face's nearest point, and OCCT's
    // search for the maxima (over all the samples) cost as much as for the minima.
    proj->SetExtremaFlag(Extrema_ExtFlag_MIN);
    it = cache.emplace(key, Entry{c.surface, std::move(proj)}).first;
  }
  return *it->second.projector;
}

struct FacePoint {
  Vec3 point;
  double u = 0, v = 0;
  bool has_uv = false;
};

// Nearest point of the trimmed face: the nearest surface extremum whose (u, v) lies inside
// the face, or else the nearest point of its boundary edges (the minimum over a trimmed
// face is either an interior critical point or on the boundary).
FacePoint nearest_on_face(const Solid& solid, const Solid::Impl& impl, int f, const Vec3& p) {
  const FaceCache& c = impl.face(f);
  FacePoint best;
  double best_d = std::numeric_limits<double>::infinity();
  bool inside_found = false;
  try {
    if (c.is_plane) {
      double u, v;
      ElSLib::Parameters(c.plane, to_pnt(p), u, v);
      const TopAbs_State s = c.classifier->perform(u, v, false);
      if (s == TopAbs_IN || s == TopAbs_ON) {
        best = {to_vec(ElSLib::Value(u, v, c.plane)), u, v, true};
        return best;
      }
    } else {
      GeomAPI_ProjectPointOnSurf& proj = projector(c);
      proj.Perform(to_pnt(p));
      for (int i = 1; i <= proj.NbPoints(); ++i) {
        const double d = proj.Distance(i);
        if (d >= best_d) continue;
        double u, v;
        proj.Parameters(i, u, v);
        const TopAbs_State s = c.classifier->perform(u, v);
        if (s == TopAbs_IN || s == TopAbs_ON) {
          best_d = d;
          best = {to_vec(proj.Point(i)), u, v, true};
          inside_found = true;
        }
      }
    }
  } catch (const Standard_Failure&) {
    inside_found = false;
    best_d = std::numeric_limits<double>::infinity();
  }
  for (int e : c.edges) {
    if (box_distance(impl.edge(e).box, p) >= best_d) continue;
    const Vec3 q = solid.project_to_edge(EdgeId(e), p);
    const double d = (q - p).norm();
    if (d < best_d) {
      best_d = d;
      best = {q, 0, 0, false};
      inside_found = true;
    }
  }
  if (!inside_found) {  // last resort: OCCT's general distance
    try {
      BRepExtrema_DistShapeShape dss(BRepBuilderAPI_MakeVertex(to_pnt(p)).Vertex(), impl.faces(f));
      if (dss.IsDone() && dss.NbSolution() > 0) best = {to_vec(dss.PointOnShape2(1)), 0, 0, false};
    } catch (const Standard_Failure&) {
    }
  }
  return best;
}

}  // namespace

Vec3 Solid::project_to_face(FaceId f, const Vec3& p) const {
  check_id(f.value(), num_faces(), "face");
  return nearest_on_face(*this, *impl_, f.value(), p).point;
}

double Solid::tolerance() const {
  double t = 0;
  for (TopExp_Explorer ex(impl_->solid, TopAbs_VERTEX); ex.More(); ex.Next())
    t = std::max(t, BRep_Tool::Tolerance(TopoDS::Vertex(ex.Current())));
  for (TopExp_Explorer ex(impl_->solid, TopAbs_EDGE); ex.More(); ex.Next())
    t = std::max(t, BRep_Tool::Tolerance(TopoDS::Edge(ex.Current())));
  for (TopExp_Explorer ex(impl_->solid, TopAbs_FACE); ex.More(); ex.Next())
    t = std::max(t, BRep_Tool::Tolerance(TopoDS::Face(ex.Current())));
  return t;
}

FaceId Solid::nearest_face(const Vec3& p) const {
  const int nf = num_faces();
  std::vector<std::pair<double, int>> order;
  order.reserve(nf);
  for (int f = 1; f <= nf; ++f) order.emplace_back(box_distance(impl_->face(f).box, p), f);
  std::sort(order.begin(), order.end());
  double best = std::numeric_limits<double>::infinity();
  int best_f = 0;
  for (const auto& [lower, f] : order) {
    if (lower >= best) break;
    const double d = (nearest_on_face(*this, *impl_, f, p).point - p).norm();
    if (d < best) best = d, best_f = f;
  }
  return FaceId(best_f);
}

EdgeId Solid::nearest_edge(const Vec3& p) const {
  double best = std::numeric_limits<double>::infinity();
  int best_e = 0;
  for (int e = 1; e <= num_edges(); ++e) {
    if (box_distance(impl_->edge(e).box, p) >= best) continue;
    const double d = distance_to_edge(EdgeId(e), p);
    if (d < best) best = d, best_e = e;
  }
  return EdgeId(best_e);
}

double Solid::distance_to_boundary(const Vec3& p) const {
  const int nf = num_faces();
  std::vector<std::pair<double, int>> order;
  order.reserve(nf);
  for (int f = 1; f <= nf; ++f) order.emplace_back(box_distance(impl_->face(f).box, p), f);
  std::sort(order.begin(), order.end());
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [lower, f] : order) {
    if (lower >= best) break;
    best = std::min(best, (nearest_on_face(*this, *impl_, f, p).point - p).norm());
  }
  return best;
}

Vec3 Solid::face_normal(FaceId f, const Vec3& p) const {
  check_id(f.value(), num_faces(), "face");
  const FaceCache& c = impl_->face(f.value());
  FacePoint fp = nearest_on_face(*this, *impl_, f.value(), p);
  gp_Vec n;
  try {
    if (!fp.has_uv) {
      GeomAPI_ProjectPointOnSurf& proj = projector(c);
      proj.Perform(to_pnt(fp.point));
      if (proj.NbPoints() > 0) proj.LowerDistanceParameters(fp.u, fp.v);
    }
    gp_Pnt q;
    gp_Vec du, dv;
    c.surface->D1(fp.u, fp.v, q, du, dv);
    n = du.Crossed(dv);
    if (n.Magnitude() < 1e-300) return Vec3::Zero();
    n.Normalize();
  } catch (const Standard_Failure&) {
    return Vec3::Zero();
  }
  Vec3 r(n.X(), n.Y(), n.Z());
  return c.reversed ? Vec3(-r) : r;
}

double Solid::interior_angle(EdgeId e, const Vec3& p, const Vec3& tangent) const {
  const std::vector<FaceId> faces = edge_faces(e);
  if (faces.size() != 2 || faces[0] == faces[1]) return std::nan("");
  Vec3 n[2], inward[2];
  for (int j = 0; j < 2; ++j) {
    int seen = 0, forward = 0;
    for (const auto& wire : face_wires(faces[j]))
      for (const OrientedEdge& oe : wire)
        if (oe.edge == e) ++seen, forward += oe.forward;
    if (seen != 1) return std::nan("");  // a seam: both sides in one face
    // Across the edge into the face: its wires run counter-clockwise seen from outside.
    n[j] = face_normal(faces[j], p);
    inward[j] = n[j].cross(forward > 0 ? tangent : Vec3(-tangent)).normalized();
  }
  const double angle = std::acos(std::clamp(inward[0].dot(inward[1]), -1.0, 1.0));
  return inward[0].dot(n[1]) > 0 ? 2 * M_PI - angle : angle;
}

core::SurfaceInfo Solid::surface_info(FaceId f) const {
  check_id(f.value(), num_faces(), "face");
  const FaceCache& c = impl_->face(f.value());
  core::SurfaceInfo info;
  try {
    GeomAdaptor_Surface s(c.surface);
    auto axis = [&](const gp_Ax1& a) {
      info.origin = to_vec(a.Location());
      info.direction = Vec3(a.Direction().X(), a.Direction().Y(), a.Direction().Z());
    };
    // A plane's normal as du x dv: its own axis may be left-handed.
    auto plane_normal = [&] {
      gp_Pnt q;
      gp_Vec du, dv;
      c.surface->D1(0.5 * (c.umin + c.umax), 0.5 * (c.vmin + c.vmax), q, du, dv);
      const gp_Vec n = du.Crossed(dv);
      return Vec3(Vec3(n.X(), n.Y(), n.Z()).normalized());
    };
    switch (s.GetType()) {
      case GeomAbs_Plane:
        info.kind = core::SurfaceKind::plane;
        info.origin = to_vec(s.Plane().Location());
        info.direction = plane_normal();
        break;
      case GeomAbs_Cylinder:
        info.kind = core::SurfaceKind::cylinder;
        axis(s.Cylinder().Axis());
        info.radius = s.Cylinder().Radius();
        break;
      case GeomAbs_Cone:
        info.kind = core::SurfaceKind::cone;
        axis(s.Cone().Axis());
        info.radius = s.Cone().RefRadius();
        break;
      case GeomAbs_Sphere:
        info.kind = core::SurfaceKind::sphere;
        info.origin = to_vec(s.Sphere().Location());
        info.radius = s.Sphere().Radius();
        break;
      case GeomAbs_Torus:
        info.kind = core::SurfaceKind::torus;
        axis(s.Torus().Axis());
        info.radius = s.Torus().MajorRadius();
        break;
      case GeomAbs_SurfaceOfRevolution: {
        info.kind = core::SurfaceKind::revolution;
        const gp_Ax1 ax = s.AxeOfRevolution();
        axis(ax);
        // A revolved line is a cylinder, a cone or a plane: some CAD systems export every
        // turned face so (HexMe's i01, i06, i07, i13, i16). Say which, so that schemes
        // looking for walls, caps and axes see the geometry, not how it was stored.
        const Handle(Adaptor3d_Curve) meridian = s.BasisCurve();
        if (meridian.IsNull() || meridian->GetType() != GeomAbs_Line) break;
        const gp_Lin line = meridian->Line();
        const double cosine = line.Direction().Dot(ax.Direction());
        const double r = gp_Lin(ax).Distance(line.Location());
        if (std::abs(cosine) > 1 - 1e-12) {
          info.kind = core::SurfaceKind::cylinder;
          info.radius = r;
        } else if (std::abs(cosine) < 1e-12) {
          info.kind = core::SurfaceKind::plane;
          info.origin = to_vec(line.Location());
          info.direction = plane_normal();
        } else {
          info.kind = core::SurfaceKind::cone;
          const gp_Vec along(ax.Location(), line.Location());
          info.origin = to_vec(
              ax.Location().Translated(along.Dot(gp_Vec(ax.Direction())) * gp_Vec(ax.Direction())));
          info.radius = r;
        }
        break;
      }
      case GeomAbs_SurfaceOfExtrusion:
        info.kind = core::SurfaceKind::extrusion;
        info.direction = Vec3(s.Direction().X(), s.Direction().Y(), s.Direction().Z());
        break;
      default:
        info.kind = c.planar ? core::SurfaceKind::plane : core::SurfaceKind::other;
        if (c.planar) {
          const Vec3 q = vertex_point(edge_first_vertex(face_wires(f)[0][0].edge));
          info.origin = q;
          info.direction = face_normal(f, q) * (c.reversed ? -1.0 : 1.0);
        }
        break;
    }
  } catch (const Standard_Failure&) {
    info = core::SurfaceInfo();
  }
  return info;
}

core::CurveInfo Solid::curve_info(EdgeId e) const {
  check_id(e.value(), num_edges(), "edge");
  const EdgeCache& c = impl_->edge(e.value());
  core::CurveInfo info;
  if (c.curve.IsNull()) return info;
  try {
    GeomAdaptor_Curve ac(c.curve, c.first, c.last);
    if (ac.GetType() == GeomAbs_Line) {
      info.kind = core::CurveKind::line;
      info.origin = to_vec(ac.Line().Location());
      const gp_Dir d = ac.Line().Direction();
      info.direction = Vec3(d.X(), d.Y(), d.Z());
    } else if (ac.GetType() == GeomAbs_Circle) {
      info.kind = core::CurveKind::circle;
      info.origin = to_vec(ac.Circle().Location());
      const gp_Dir d = ac.Circle().Axis().Direction();
      info.direction = Vec3(d.X(), d.Y(), d.Z());
      info.radius = ac.Circle().Radius();
    }
  } catch (const Standard_Failure&) {
    info = core::CurveInfo();
  }
  return info;
}

std::unique_ptr<core::SurfaceChart> Solid::face_chart(FaceId f) const {
  check_id(f.value(), num_faces(), "face");
  return std::make_unique<FaceChart>(*this, f);
}

std::string Solid::to_brep_string() const {
  std::ostringstream out;
  BRepTools::Write(impl_->solid, out);
  return out.str();
}

}  // namespace vorohex::occ
