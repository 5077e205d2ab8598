#include "occ/revolution.h"

#include <BRepAdaptor_Surface.hxx>
#include <BRepAlgoAPI_Common.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepGProp.hxx>
#include <BRep_Builder.hxx>
#include <GProp_GProps.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>

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

bool same_line(const Line& l, const gp_Ax1& ax, double tol) {
  const Vec3 d = to_vec(ax.Direction().XYZ());
  return std::abs(std::abs(d.dot(l.a)) - 1) < 1e-9 &&
         distance_to_line(l, to_vec(ax.Location().XYZ())) <= tol;
}

// The axis of a face of revolution (none for planes, spheres and other surfaces).
bool face_axis(const GeomAdaptor_Surface& s, gp_Ax1& ax) {
  switch (s.GetType()) {
    case GeomAbs_Cylinder:
      ax = s.Cylinder().Axis();
      return true;
    case GeomAbs_Cone:
      ax = s.Cone().Axis();
      return true;
    case GeomAbs_Torus:
      ax = s.Torus().Axis();
      return true;
    case GeomAbs_SurfaceOfRevolution:
      ax = s.AxeOfRevolution();
      return true;
    default:
      return false;
  }
}

std::vector<Line> candidate_axes(const Solid& solid, double tol) {
  std::vector<Line> out;
  for (FaceId f : solid.faces()) {
    GeomAdaptor_Surface s(solid.impl().face(f.value()).surface);
    gp_Ax1 ax;
    if (!face_axis(s, ax)) continue;
    bool known = false;
    for (const Line& l : out) known = known || same_line(l, ax, tol);
    if (known) continue;
    // The sign that makes the largest component positive: the same axis however the face
    // that gives it is oriented.
    Vec3 d = to_vec(ax.Direction().XYZ()).normalized();
    int big = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(d[k]) > std::abs(d[big]) + 1e-12) big = k;
    if (d[big] < 0) d = -d;
    out.push_back({to_vec(ax.Location().XYZ()), d});
  }
  return out;
}

// Whether every face and edge is of revolution about `l`, or the reason why not.
std::string check(const Solid& solid, const Line& l, double tol) {
  for (FaceId f : solid.faces()) {
    const FaceCache& c = solid.impl().face(f.value());
    GeomAdaptor_Surface s(c.surface);
    gp_Ax1 ax;
    if (s.GetType() == GeomAbs_Plane || (c.planar && !face_axis(s, ax))) {
      const Vec3 q = solid.vertex_point(solid.edge_first_vertex(solid.face_wires(f)[0][0].edge));
      if (std::abs(std::abs(solid.face_normal(f, q).dot(l.a)) - 1) > 1e-9)
        return face_name(f.value()) + " is a plane not perpendicular to the axis";
    } else if (face_axis(s, ax)) {
      if (!same_line(l, ax, tol)) return face_name(f.value()) + " turns about another axis";
    } else if (s.GetType() == GeomAbs_Sphere) {
      if (distance_to_line(l, to_vec(s.Sphere().Location().XYZ())) > tol)
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
Vec3 section_direction(const Solid& solid, const Line& l, double tol) {
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

RevolutionStructure structure_for(const Solid& solid, const Line& l, double tol) {
  RevolutionStructure r;
  r.origin = l.o;
  r.axis = l.a;
  r.reason = check(solid, l, tol);
  if (!r.reason.empty()) return r;
  r.radial = section_direction(solid, l, tol);
  const Vec3 normal = r.axis.cross(r.radial);
  // The half-plane, a little larger than the solid.
  const BoundingBox box = solid.bounding_box();
  double zmin = 1e300, zmax = -1e300, rmax = 0;
  for (int i = 0; i < 8; ++i) {
    const Vec3 c((i & 1) ? box.max.x() : box.min.x(), (i & 2) ? box.max.y() : box.min.y(),
                 (i & 4) ? box.max.z() : box.min.z());
    zmin = std::min(zmin, r.height(c)), zmax = std::max(zmax, r.height(c));
    rmax = std::max(rmax, r.radius(c));
  }
  const double pad = 0.01 * box.diagonal() + 10 * tol;
  const TopoDS_Face half =
      rectangle(r.origin, r.axis, r.radial, 0, rmax + pad, zmin - pad, zmax + pad);
  BRepAlgoAPI_Common common(solid.impl().solid, half);
  if (!common.IsDone() || common.HasErrors()) {
    r.reason = "its meridian section could not be computed (OCCT's common failed)";
    return r;
  }
  TopoDS_Compound section = oriented_faces(common.Shape(), normal);
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

RevolutionStructure revolution_structure(const Solid& solid) {
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
