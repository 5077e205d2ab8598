#include "occ/revolution.h"

#include <BRepAdaptor_Surface.hxx>
#include <BRepAlgoAPI_Common.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepGProp.hxx>
#include <BRep_Builder.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <GProp_GProps.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <ShapeFix_Face.hxx>
#include <Standard_Failure.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <gp_Ax2.hxx>
#include <gp_Circ.hxx>
#include <gp_Pln.hxx>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "occ/solid_impl.h"

namespace vorohex::occ {
namespace {

const double kPi = 3.14159265358979323846;

Vec3 to_vec(const gp_XYZ& p) {
  return Vec3(p.X(), p.Y(), p.Z());
}
gp_Pnt to_pnt(const Vec3& p) {
  return gp_Pnt(p.x(), p.y(), p.z());
}
std::string face_name(int f) {
  return "Face" + std::to_string(f);
}
std::string edge_name(int e) {
  return "Edge" + std::to_string(e);
}

struct Line {
  Vec3 o, a;
};

double distance_to_line(const Line& l, const Vec3& p) {
  const Vec3 d = p - l.o;
  return (d - d.dot(l.a) * l.a).norm();
}

// The axis of a face of revolution (none for planes, spheres and other surfaces).
bool face_axis(const core::SurfaceInfo& s, Line& ax) {
  switch (s.kind) {
    case core::SurfaceKind::cylinder:
    case core::SurfaceKind::cone:
    case core::SurfaceKind::torus:
    case core::SurfaceKind::revolution:
      if (!(s.direction.norm() > 0)) return false;
      ax = {s.origin, s.direction.normalized()};
      return true;
    default:
      return false;
  }
}

bool same_line(const Line& l, const Line& ax, double tol) {
  return std::abs(std::abs(ax.a.dot(l.a)) - 1) < 1e-9 && distance_to_line(l, ax.o) <= tol;
}

std::vector<Line> candidate_axes(const core::MeshDomain& solid, double tol) {
  std::vector<Line> out;
  for (FaceId f : solid.faces()) {
    Line ax;
    if (!face_axis(solid.surface_info(f), ax)) continue;
    bool known = false;
    for (const Line& l : out) known = known || same_line(l, ax, tol);
    if (known) continue;
    // The sign that makes the largest component positive: the same axis however the face
    // that gives it is oriented.
    Vec3 d = ax.a;
    int big = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(d[k]) > std::abs(d[big]) + 1e-12) big = k;
    if (d[big] < 0) d = -d;
    out.push_back({ax.o, d});
  }
  return out;
}

// Whether every face and edge is of revolution about `l`, or the reason why not.
std::string check(const core::MeshDomain& solid, const Line& l, double tol) {
  for (FaceId f : solid.faces()) {
    const core::SurfaceInfo s = solid.surface_info(f);
    Line ax;
    if (s.kind == core::SurfaceKind::plane) {
      if (std::abs(std::abs(s.direction.dot(l.a)) - 1) > 1e-9)
        return face_name(f.value()) + " is a plane not perpendicular to the axis";
    } else if (face_axis(s, ax)) {
      if (!same_line(l, ax, tol)) return face_name(f.value()) + " turns about another axis";
    } else if (s.kind == core::SurfaceKind::sphere) {
      if (distance_to_line(l, s.origin) > tol)
        return face_name(f.value()) + " is a sphere off the axis";
    } else {
      return face_name(f.value()) + " is not a surface of revolution";
    }
  }
  for (EdgeId e : solid.edges()) {
    if (solid.edge_is_degenerated(e)) continue;
    const std::vector<Vec3> p = solid.edge_points_by_length(e, 16);
    bool parallel = true, meridian = true;
    Vec3 dir = Vec3::Zero();
    const double h0 = (p[0] - l.o).dot(l.a), r0 = distance_to_line(l, p[0]);
    for (const Vec3& q : p) {
      const Vec3 d = q - l.o;
      const Vec3 radial = d - d.dot(l.a) * l.a;
      parallel =
          parallel && std::abs(d.dot(l.a) - h0) <= tol && std::abs(radial.norm() - r0) <= tol;
      if (radial.norm() > tol) {
        if (dir.norm() == 0) dir = radial.normalized();
        meridian =
            meridian && (radial - radial.dot(dir) * dir).norm() <= tol && radial.dot(dir) > 0;
      }
    }
    if (!parallel && !meridian)
      return edge_name(e.value()) + " is neither a circle about the axis nor in a plane through it";
  }
  return "";
}

// A unit vector across the axis in the middle of the widest angular gap between the
// vertices off the axis: the section's half-plane then passes through no vertex or seam.
Vec3 section_direction(const core::MeshDomain& solid, const Line& l, double tol) {
  const Vec3 u = l.a.unitOrthogonal(), v = l.a.cross(u);
  std::vector<double> angles;
  for (VertexId vx : solid.vertices()) {
    const Vec3 d = solid.vertex_point(vx) - l.o;
    const Vec3 radial = d - d.dot(l.a) * l.a;
    if (radial.norm() > tol) angles.push_back(std::atan2(radial.dot(v), radial.dot(u)));
  }
  double theta = 0.5;  // arbitrary when no vertex is off the axis
  if (!angles.empty()) {
    std::sort(angles.begin(), angles.end());
    double best = -1;
    for (std::size_t i = 0; i < angles.size(); ++i) {
      const double a = angles[i];
      const double b = i + 1 < angles.size() ? angles[i + 1] : angles[0] + 2 * kPi;
      if (b - a > best) best = b - a, theta = 0.5 * (a + b);
    }
  }
  return std::cos(theta) * u + std::sin(theta) * v;
}

// The meridian section in the half-plane through the axis along `er`, built from the
// faces' traces (no boolean with the solid): each face of revolution meets the half-plane in
// one curve between its two parallels (or a parallel and the axis), of known shape: a
// straight segment for planes, cylinders and cones, an arc for spheres and tori, sampled by
// projection onto the face for other surfaces of revolution; a full torus in a circle. The
// traces' ends are joined, the axis closes the section where traces end on it.
class SectionBuilder {
 public:
  SectionBuilder(const core::MeshDomain& solid, const Line& l, const Vec3& er, double tol)
      : solid_(solid), l_(l), er_(er), tol_(tol) {}

  // The section's planar face(s), or a null shape with `why` set.
  TopoDS_Shape build(std::string& why) {
    for (FaceId f : solid_.faces())
      if (!trace(f, why)) return TopoDS_Shape();
    if (!close_on_axis(why)) return TopoDS_Shape();
    return make_face(why);
  }

 private:
  struct Rz {
    double r = 0, z = 0;
  };
  struct Trace {
    std::vector<Rz> points;  // first to last; closed when first == last node and one edge
    int from = -1, to = -1;  // node ids
    bool arc = false;        // points[1] is the arc's middle
    double circle = 0;       // > 0: a whole circle of this radius about `centre`
    Rz centre;
  };

  Vec3 lift(const Rz& q) const { return l_.o + q.z * l_.a + q.r * er_; }
  Rz rz(const Vec3& p) const {
    const Vec3 d = p - l_.o;
    return {(d - d.dot(l_.a) * l_.a).norm(), d.dot(l_.a)};
  }
  int node(const Rz& q) {
    for (std::size_t i = 0; i < nodes_.size(); ++i)
      if (std::hypot(nodes_[i].r - q.r, nodes_[i].z - q.z) <= 10 * tol_) return int(i);
    nodes_.push_back(q.r <= tol_ ? Rz{0, q.z} : q);
    return int(nodes_.size()) - 1;
  }

  // Whether edge e is a parallel (a circle about the axis, off it), with its (r, z).
  bool parallel(EdgeId e, Rz& out) const {
    const std::vector<Vec3> p = solid_.edge_points_by_length(e, 8);
    const Rz a = rz(p.front());
    if (a.r <= tol_) return false;
    for (const Vec3& q : p) {
      const Rz b = rz(q);
      if (std::abs(b.r - a.r) > tol_ || std::abs(b.z - a.z) > tol_) return false;
    }
    out = a;
    return true;
  }
  // A parallel's arc reaches the half-plane when the half-plane's point on it lies on it.
  bool crosses(EdgeId e, const Rz& q) const {
    return solid_.distance_to_edge(e, lift(q)) <= 10 * tol_;
  }

  bool trace(FaceId f, std::string& why) {
    const core::SurfaceInfo info = solid_.surface_info(f);
    std::vector<Rz> ends;
    bool misses_half_plane = false;
    for (const auto& wire : solid_.face_wires(f))
      for (const core::OrientedEdge& oe : wire) {
        Rz q;
        if (solid_.edge_is_degenerated(oe.edge)) {
          q = rz(solid_.vertex_point(solid_.edge_first_vertex(oe.edge)));
          if (q.r <= tol_) ends.push_back({0, q.z});
        } else if (parallel(oe.edge, q)) {
          if (crosses(oe.edge, q))
            ends.push_back(q);
          else
            misses_half_plane = true;
        }
      }
    if (ends.empty() && misses_half_plane) return true;  // a face on the other side of a seam
    if (info.kind == core::SurfaceKind::plane && ends.size() == 1) ends.push_back({0, ends[0].z});
    const std::string name = face_name(f.value());
    const bool seam_twice =
        ends.size() == 2 && std::hypot(ends[0].r - ends[1].r, ends[0].z - ends[1].z) <= 10 * tol_;
    if ((ends.empty() || seam_twice) && info.kind == core::SurfaceKind::torus) {
      // A whole torus (its wire may run twice along a parallel seam): its tube's circle,
      // from that seam's point or, with none, from a projected point.
      const Rz c{info.radius, (info.origin - l_.o).dot(l_.a)};
      const Rz on = seam_twice
                        ? ends[0]
                        : rz(solid_.project_to_face(f, lift({c.r + 0.5 * info.radius, c.z})));
      const double rho = std::hypot(on.r - c.r, on.z - c.z);
      const double a0 = std::atan2(on.z - c.z, on.r - c.r);
      Trace t;
      t.circle = rho;
      t.centre = c;
      for (int k = 0; k <= 64; ++k) {
        const double a = a0 + 2 * kPi * k / 64;
        t.points.push_back({c.r + rho * std::cos(a), c.z + rho * std::sin(a)});
      }
      t.from = t.to = node(t.points.front());
      t.points.back() = t.points.front();
      closed_.push_back(t);
      return true;
    }
    if (ends.size() != 2) {
      why = name + " meets the meridian section " + std::to_string(ends.size()) +
            " times, not at two ends";
      return false;
    }
    Trace t;
    t.from = node(ends[0]);
    t.to = node(ends[1]);
    const Rz a = nodes_[t.from], b = nodes_[t.to];
    switch (info.kind) {
      case core::SurfaceKind::plane:
      case core::SurfaceKind::cylinder:
      case core::SurfaceKind::cone:
        t.points = {a, b};
        break;
      case core::SurfaceKind::sphere:
      case core::SurfaceKind::torus: {
        const Rz c = info.kind == core::SurfaceKind::sphere
                         ? Rz{0, (info.origin - l_.o).dot(l_.a)}
                         : Rz{info.radius, (info.origin - l_.o).dot(l_.a)};
        const double rho = std::hypot(a.r - c.r, a.z - c.z);
        const double a0 = std::atan2(a.z - c.z, a.r - c.r);
        double sweep = std::atan2(b.z - c.z, b.r - c.r) - a0;
        while (sweep <= 0) sweep += 2 * kPi;
        // The arc one way or the other round the centre: the one the face holds.
        for (const double dir : {1.0, -1.0}) {
          const double span = dir > 0 ? sweep : 2 * kPi - sweep;
          const double mid = a0 + dir * 0.5 * span;
          const Rz m{c.r + rho * std::cos(mid), c.z + rho * std::sin(mid)};
          if (m.r >= -tol_ && solid_.distance_to_face(f, lift(m)) <= 100 * tol_) {
            t.points = {a, m, b};
            t.arc = true;
            break;
          }
        }
        if (t.points.empty()) {
          why = name + "'s meridian arc could not be found";
          return false;
        }
        break;
      }
      default: {
        // A meridian edge of the face (its seam, or a side of a split face) is the trace
        // turned about the axis; else points of the chord projected onto the face.
        const int n = 64;
        for (const auto& wire : solid_.face_wires(f))
          for (const core::OrientedEdge& oe : wire) {
            if (!t.points.empty() || solid_.edge_is_degenerated(oe.edge)) continue;
            std::vector<Vec3> p = solid_.edge_points_by_length(oe.edge, n);
            const Rz p0 = rz(p.front()), p1 = rz(p.back());
            auto near = [&](const Rz& x, const Rz& y) {
              return std::hypot(x.r - y.r, x.z - y.z) <= 10 * tol_;
            };
            if (near(p0, p1)) continue;  // a parallel
            if (near(p0, b) && near(p1, a))
              std::reverse(p.begin(), p.end());
            else if (!(near(p0, a) && near(p1, b)))
              continue;
            for (const Vec3& q : p) t.points.push_back(rz(q));
            t.points.front() = a, t.points.back() = b;
          }
        for (int k = 0; t.points.empty() && k <= n; ++k) {
          const double s = double(k) / n;
          const Rz q{a.r + s * (b.r - a.r), a.z + s * (b.z - a.z)};
          t.points.push_back(k == 0 ? a : k == n ? b : rz(solid_.project_to_face(f, lift(q))));
        }
        break;
      }
    }
    traces_.push_back(t);
    return true;
  }

  // Ends on the axis joined two by two along it (in the order of their heights).
  bool close_on_axis(std::string& why) {
    std::vector<int> degree(nodes_.size(), 0);
    for (const Trace& t : traces_) ++degree[t.from], ++degree[t.to];
    std::vector<int> open;
    for (std::size_t i = 0; i < nodes_.size(); ++i)
      if (degree[i] % 2) {
        if (nodes_[i].r > tol_) {
          why = "its meridian section is not closed at r = " + std::to_string(nodes_[i].r) +
                ", z = " + std::to_string(nodes_[i].z);
          return false;
        }
        open.push_back(int(i));
      }
    std::sort(open.begin(), open.end(), [&](int x, int y) { return nodes_[x].z < nodes_[y].z; });
    for (std::size_t k = 0; k + 1 < open.size(); k += 2) {
      Trace t;
      t.from = open[k];
      t.to = open[k + 1];
      t.points = {nodes_[t.from], nodes_[t.to]};
      traces_.push_back(t);
    }
    return true;
  }

  TopoDS_Edge edge_of(const Trace& t) const {
    auto pnt = [&](const Rz& q) {
      const Vec3 p = lift(q);
      return gp_Pnt(p.x(), p.y(), p.z());
    };
    if (t.points.size() == 2)
      return BRepBuilderAPI_MakeEdge(pnt(t.points[0]), pnt(t.points[1])).Edge();
    if (t.circle > 0) {
      const Vec3 n = l_.a.cross(er_);
      const gp_Ax2 frame(pnt(t.centre), gp_Dir(n.x(), n.y(), n.z()),
                         gp_Dir(er_.x(), er_.y(), er_.z()));
      return BRepBuilderAPI_MakeEdge(gp_Circ(frame, t.circle)).Edge();
    }
    if (t.arc) {
      GC_MakeArcOfCircle arc(pnt(t.points[0]), pnt(t.points[1]), pnt(t.points[2]));
      return BRepBuilderAPI_MakeEdge(arc.Value()).Edge();
    }
    const bool closed = t.from == t.to;
    Handle(TColgp_HArray1OfPnt) pts =
        new TColgp_HArray1OfPnt(1, int(t.points.size()) - (closed ? 1 : 0));
    for (int i = 1; i <= pts->Length(); ++i) pts->SetValue(i, pnt(t.points[i - 1]));
    GeomAPI_Interpolate interpolate(pts, closed, 1e-9);
    interpolate.Perform();
    if (!interpolate.IsDone()) throw std::runtime_error("a meridian curve cannot be interpolated");
    return BRepBuilderAPI_MakeEdge(interpolate.Curve()).Edge();
  }

  // Loops walked through the nodes (each of degree two), the largest outer.
  TopoDS_Shape make_face(std::string& why) {
    std::vector<std::vector<int>> at(nodes_.size());
    for (std::size_t i = 0; i < traces_.size(); ++i)
      at[traces_[i].from].push_back(int(i)), at[traces_[i].to].push_back(int(i));
    for (const auto& a : at)
      if (a.size() > 2) {
        why = "its meridian section touches itself";
        return TopoDS_Shape();
      }
    std::vector<char> used(traces_.size(), 0);
    std::vector<std::pair<double, TopoDS_Wire>> wires;
    auto add_wire = [&](const std::vector<const Trace*>& loop) {
      BRepBuilderAPI_MakeWire mw;
      double area = 0;
      for (const Trace* t : loop) {
        mw.Add(edge_of(*t));
        for (std::size_t k = 0; k + 1 < t->points.size(); ++k)
          area += t->points[k].r * t->points[k + 1].z - t->points[k + 1].r * t->points[k].z;
      }
      if (!mw.IsDone()) return false;
      wires.emplace_back(std::abs(area), mw.Wire());
      return true;
    };
    for (std::size_t start = 0; start < traces_.size(); ++start) {
      if (used[start]) continue;
      std::vector<const Trace*> loop;
      std::size_t cur = start;
      int at_node = traces_[start].from;
      while (!used[cur]) {
        used[cur] = 1;
        loop.push_back(&traces_[cur]);
        const int next_node = traces_[cur].from == at_node ? traces_[cur].to : traces_[cur].from;
        at_node = next_node;
        for (int j : at[next_node])
          if (!used[j]) cur = std::size_t(j);
      }
      if (loop.back()->to != traces_[start].from && loop.back()->from != traces_[start].from &&
          loop.size() > 1) {
        why = "its meridian section is not a closed curve";
        return TopoDS_Shape();
      }
      if (!add_wire(loop)) {
        why = "its meridian section's curves do not join";
        return TopoDS_Shape();
      }
    }
    for (const Trace& t : closed_)
      if (!add_wire({&t})) {
        why = "its meridian section's curves do not join";
        return TopoDS_Shape();
      }
    if (wires.empty()) {
      why = "its meridian section is empty";
      return TopoDS_Shape();
    }
    std::sort(wires.begin(), wires.end(),
              [](const auto& x, const auto& y) { return x.first > y.first; });
    const Vec3 n = l_.a.cross(er_);
    const gp_Pln plane(gp_Pnt(l_.o.x(), l_.o.y(), l_.o.z()), gp_Dir(n.x(), n.y(), n.z()));
    BRepBuilderAPI_MakeFace mf(plane, wires[0].second, true);
    for (std::size_t i = 1; i < wires.size(); ++i) mf.Add(wires[i].second);
    if (!mf.IsDone()) {
      why = "its meridian section could not be made a face";
      return TopoDS_Shape();
    }
    ShapeFix_Face fix(mf.Face());
    fix.FixOrientation();
    fix.Perform();
    return fix.Face();
  }

  const core::MeshDomain& solid_;
  Line l_;
  Vec3 er_;
  double tol_;
  std::vector<Rz> nodes_;
  std::vector<Trace> traces_, closed_;
};

TopoDS_Face rectangle(const Vec3& o, const Vec3& a, const Vec3& er, double r0, double r1, double z0,
                      double z1) {
  BRepBuilderAPI_MakePolygon poly;
  for (const auto& [r, z] : {std::pair{r0, z0}, {r1, z0}, {r1, z1}, {r0, z1}})
    poly.Add(to_pnt(o + z * a + r * er));
  poly.Close();
  return BRepBuilderAPI_MakeFace(poly.Wire(), true).Face();
}

double area(const TopoDS_Shape& s) {
  GProp_GProps props;
  BRepGProp::SurfaceProperties(s, props);
  return props.Mass();
}

// The faces of `s` oriented with normal n, as one compound.
TopoDS_Compound oriented_faces(const TopoDS_Shape& s, const Vec3& n) {
  BRep_Builder b;
  TopoDS_Compound out;
  b.MakeCompound(out);
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(s, TopAbs_FACE, faces);
  for (int i = 1; i <= faces.Extent(); ++i) {
    TopoDS_Face f = TopoDS::Face(faces(i));
    BRepAdaptor_Surface as(f, false);
    gp_Pnt q;
    gp_Vec du, dv;
    as.D1(0.5 * (as.FirstUParameter() + as.LastUParameter()),
          0.5 * (as.FirstVParameter() + as.LastVParameter()), q, du, dv);
    Vec3 fn = to_vec(du.Crossed(dv).XYZ());
    if (f.Orientation() == TopAbs_REVERSED) fn = -fn;
    if (fn.dot(n) < 0) f.Reverse();
    b.Add(out, f);
  }
  return out;
}

RevolutionStructure structure_for(const core::MeshDomain& solid, const Line& l, double tol) {
  RevolutionStructure r;
  r.origin = l.o;
  r.axis = l.a;
  r.reason = check(solid, l, tol);
  if (!r.reason.empty()) return r;
  r.radial = section_direction(solid, l, tol);
  const Vec3 normal = r.axis.cross(r.radial);
  SectionBuilder builder(solid, l, r.radial, tol);
  const TopoDS_Shape built = builder.build(r.reason);
  if (built.IsNull()) {
    if (r.reason.empty()) r.reason = "its meridian section could not be built";
    return r;
  }
  TopoDS_Compound section = oriented_faces(built, normal);
  const double section_area = area(section);
  if (!(section_area > 0)) {
    r.reason = "its meridian section is empty";
    return r;
  }
  // Volume by Pappus (2 pi x the section's first moment about the axis) against the solid's:
  // a section that misses material (a boolean that went wrong) is no section.
  {
    GProp_GProps props;
    BRepGProp::SurfaceProperties(section, props);
    const double pappus = 2 * kPi * r.radius(to_vec(props.CentreOfMass().XYZ())) * props.Mass();
    if (std::abs(pappus - solid.volume()) > 1e-6 * solid.volume()) {
      r.reason = "its meridian section does not turn into its volume";
      return r;
    }
  }
  const Solid whole(make_solid_impl(section));

  // Cores: where the section lies on the axis, between two of the solid's planes.
  std::vector<std::pair<double, double>> on_axis;
  for (EdgeId e : whole.edges()) {
    const std::vector<Vec3> p = whole.edge_points_by_length(e, 4);
    bool axial = true;
    for (const Vec3& q : p) axial = axial && r.radius(q) <= tol;
    if (axial)
      on_axis.emplace_back(std::min(r.height(p.front()), r.height(p.back())),
                           std::max(r.height(p.front()), r.height(p.back())));
  }
  std::sort(on_axis.begin(), on_axis.end());
  std::vector<std::pair<double, double>> merged;
  for (const auto& s : on_axis)
    if (!merged.empty() && s.first <= merged.back().second + tol)
      merged.back().second = std::max(merged.back().second, s.second);
    else
      merged.push_back(s);
  for (const auto& [z0, z1] : merged) {
    RevolutionCore core;
    core.z0 = z0;
    core.z1 = z1;
    double reach = 1e300;
    for (double z : {z0, z1}) {
      // The section's edge leaving the axis at height z must run across it (a plane).
      bool found = false;
      for (EdgeId e : whole.edges()) {
        const Vec3 a = whole.vertex_point(whole.edge_first_vertex(e));
        const Vec3 b = whole.vertex_point(whole.edge_last_vertex(e));
        const bool at_a = r.radius(a) <= tol && std::abs(r.height(a) - z) <= tol;
        const bool at_b = r.radius(b) <= tol && std::abs(r.height(b) - z) <= tol;
        if (!(at_a || at_b) || (r.radius(a) <= tol && r.radius(b) <= tol)) continue;
        found = true;
        const std::vector<Vec3> p = whole.edge_points_by_length(e, 8);
        for (const Vec3& q : p)
          if (std::abs(r.height(q) - z) > tol) {
            std::ostringstream why;
            why << "its section meets the axis at an angle at height " << z
                << " (a cone's apex or a sphere's pole)";
            r.reason = why.str();
            return r;
          }
        reach = std::min(reach, whole.edge_length(e));
        const FaceId cap = solid.nearest_face(r.origin + z * r.axis);
        (z == z0 ? core.bottom : core.top) = cap;
      }
      if (!found) {
        r.reason = "its section touches the axis at a point only";
        return r;
      }
    }
    r.core_radius = r.core_radius == 0 ? 0.5 * reach : std::min(r.core_radius, 0.5 * reach);
    r.cores.push_back(core);
  }
  TopoDS_Shape rest = section;
  if (!r.cores.empty()) {
    // The cores must lie inside the section; a thinner core where they do not.
    for (int attempt = 0;; ++attempt) {
      bool inside = true;
      for (const RevolutionCore& c : r.cores) {
        const TopoDS_Face rect =
            rectangle(r.origin, r.axis, r.radial, 0, r.core_radius, c.z0, c.z1);
        BRepAlgoAPI_Common in(section, rect);
        inside =
            inside && in.IsDone() && std::abs(area(in.Shape()) - area(rect)) <= 1e-9 * section_area;
      }
      if (inside) break;
      if (attempt == 4) {
        r.reason = "no coaxial core fits inside its section";
        return r;
      }
      r.core_radius *= 0.5;
    }
    TopTools_ListOfShape arguments, tools;
    arguments.Append(section);
    for (const RevolutionCore& c : r.cores)
      tools.Append(rectangle(r.origin, r.axis, r.radial, 0, r.core_radius, c.z0, c.z1));
    BRepAlgoAPI_Cut cut;
    cut.SetArguments(arguments);
    cut.SetTools(tools);
    cut.Build();
    if (!cut.IsDone() || cut.HasErrors()) {
      r.reason = "the cores could not be cut out of its section";
      return r;
    }
    rest = cut.Shape();
  }
  r.section = std::make_unique<Solid>(make_solid_impl(oriented_faces(rest, normal)));
  if (r.section->num_faces() == 0) {
    r.reason = "nothing of its section is left around the cores";
    return r;
  }
  r.core_side.assign(r.section->num_edges() + 1, false);
  for (EdgeId e : r.section->edges()) {
    const std::vector<Vec3> p = r.section->edge_points_by_length(e, 8);
    for (const Vec3& q : p) r.max_radius = std::max(r.max_radius, r.radius(q));
    if (r.cores.empty()) continue;
    bool side = true;
    for (const Vec3& q : p) side = side && std::abs(r.radius(q) - r.core_radius) <= tol;
    const double zm = r.height(p[4]);
    bool within = false;
    for (const RevolutionCore& c : r.cores) within = within || (zm > c.z0 + tol && zm < c.z1 - tol);
    r.core_side[e.value()] = side && within;
  }
  r.ok = true;
  return r;
}

}  // namespace

RevolutionStructure revolution_structure(const core::MeshDomain& solid) {
  RevolutionStructure best;
  best.reason = "it has no cylinder, cone, torus or surface of revolution";
  try {
    const double tol = std::max(1e-6 * solid.diagonal(), 2 * solid.tolerance());
    std::string first_reason;
    for (const Line& l : candidate_axes(solid, tol)) {
      RevolutionStructure s = structure_for(solid, l, tol);
      if (s.ok) return s;
      if (first_reason.empty()) first_reason = s.reason;
    }
    if (!first_reason.empty()) best.reason = first_reason;
  } catch (const Standard_Failure& e) {
    best = RevolutionStructure();
    best.reason = std::string("its geometry cannot be analysed (") + e.GetMessageString() + ")";
  } catch (const std::exception& e) {
    best = RevolutionStructure();
    best.reason = std::string("its geometry cannot be analysed (") + e.what() + ")";
  }
  return best;
}

}  // namespace vorohex::occ
