#include "decompose/detail/foot_planes.h"

#include <algorithm>
#include <cmath>

#include "occ/prismatic.h"

namespace vorohex::decompose::detail {

using core::EdgeId;
using core::FaceId;
using core::Vec3;

namespace {

// What a face is to the feet planes, found once: a planar face (a plane, or a B-spline that
// is flat, as lofts leave them) with its unit normal, a cylinder, a cone or a torus with its
// unit axis, or another face (no direction). `convex`: a cylinder or torus bulging out of
// the solid (its axis, or its tube's centre circle, inside it: a rounded edge's fillet).
struct FaceAxis {
  enum Kind { other, planar, cylinder, cone, torus } kind = other;
  Vec3 d = Vec3::Zero();
  bool convex = false;
};

// Whether cylinder or torus f bulges out of the solid: its outward normal at a point of an
// edge of it points away from the centre of its curvature there.
bool bulges(const occ::Solid& s, FaceId f, const core::SurfaceInfo& info) {
  const auto wires = s.face_wires(f);
  if (wires.empty() || wires[0].empty()) return false;
  const std::vector<Vec3> pts = s.edge_points_by_length(wires[0][0].edge, 2);
  const Vec3 p = pts[pts.size() / 2];
  const Vec3 d = info.direction.normalized();
  Vec3 from_axis = (p - info.origin) - d * d.dot(p - info.origin);
  if (info.kind == core::SurfaceKind::torus) {
    if (from_axis.norm() == 0) return false;
    from_axis = (p - info.origin) - from_axis.normalized() * info.radius;  // from the tube's centre
  }
  return s.face_normal(f, p).dot(from_axis) > 0;
}

FaceAxis face_axis(const occ::Solid& s, FaceId f) {
  FaceAxis out;
  if (s.face_is_planar(f)) {
    const auto wires = s.face_wires(f);
    if (wires.empty() || wires[0].empty()) return out;
    const Vec3 n = s.face_normal(f, s.vertex_point(s.edge_first_vertex(wires[0][0].edge)));
    if (n.norm() > 0) out = {FaceAxis::planar, n.normalized()};
    return out;
  }
  const core::SurfaceInfo info = s.surface_info(f);
  if (info.direction.norm() == 0) return out;
  if (info.kind == core::SurfaceKind::cylinder)
    out = {FaceAxis::cylinder, info.direction.normalized(), bulges(s, f, info)};
  if (info.kind == core::SurfaceKind::cone) out = {FaceAxis::cone, info.direction.normalized()};
  if (info.kind == core::SurfaceKind::torus)
    out = {FaceAxis::torus, info.direction.normalized(), bulges(s, f, info)};
  return out;
}

// Parallel to axis a (a wall): a planar face whose normal is across it, a cylinder along it.
bool wall(const FaceAxis& f, const Vec3& a) {
  const double c = std::abs(f.d.dot(a));
  return (f.kind == FaceAxis::planar && c < 1e-9) ||
         (f.kind == FaceAxis::cylinder && std::abs(c - 1) < 1e-9);
}

// Across axis a (a cap): a planar face whose normal is along it.
bool cap(const FaceAxis& f, const Vec3& a) {
  return f.kind == FaceAxis::planar && std::abs(std::abs(f.d.dot(a)) - 1) < 1e-9;
}

// Tapered to axis a: a planar face neither along nor across it, or a cone about it.
bool tapered(const FaceAxis& f, const Vec3& a) {
  const double c = std::abs(f.d.dot(a));
  return (f.kind == FaceAxis::planar && c > 1e-6 && c < 1 - 1e-6) ||
         (f.kind == FaceAxis::cone && std::abs(c - 1) < 1e-9);
}

// A rounded edge across axis a (a fillet): a cylinder across it or a torus about it, bulging
// out of the solid. Where it meets a wall, tangent to it, the cut across its foot leaves it
// on a slab that is a mapped block or a sweep (a block with its top edges filleted: a block
// and a slab whose fillets are its sides); the concave fillet at a pocket's floor is no
// foot: a cut there leaves a knife edge where it meets the floor tangentially.
bool rounded(const FaceAxis& f, const Vec3& a) {
  const double c = std::abs(f.d.dot(a));
  return f.convex && ((f.kind == FaceAxis::cylinder && c < 1e-9) ||
                      (f.kind == FaceAxis::torus && std::abs(c - 1) < 1e-9));
}

// A concave fillet across axis a between two walls: a cylinder across it whose axis lies
// outside the solid (an L bracket's inner edge rounded). Where it meets a wall along the axis,
// tangent to it, the plane across a there passes through the fillet's axis and meets the
// fillet at a right angle, as the plane of a face at a concave edge would: no knife edge.
bool concave_round(const FaceAxis& f, const Vec3& a) {
  return !f.convex && f.kind == FaceAxis::cylinder && std::abs(f.d.dot(a)) < 1e-9;
}

}  // namespace

std::vector<FootPlaneSet> foot_plane_sets(const occ::Solid& solid) {
  const double tol = 1e-7 * solid.diagonal();
  std::vector<FaceAxis> faces(solid.num_faces() + 1);
  std::vector<Vec3> axes;
  for (FaceId f : solid.faces()) {
    const FaceAxis& fa = faces[f.value()] = face_axis(solid, f);
    if (fa.kind != FaceAxis::planar && fa.kind != FaceAxis::cylinder) continue;
    bool known = false;
    for (const Vec3& o : axes) known = known || std::abs(o.dot(fa.d)) > 1 - 1e-9;
    if (!known) axes.push_back(fa.d);
  }
  std::vector<FootPlaneSet> sets;
  for (const Vec3& a : axes) {
    // The solid's extent along a: a foot plane at either end cuts nothing off.
    double lo = 1e300, hi = -1e300;
    for (core::VertexId v : solid.vertices()) {
      lo = std::min(lo, a.dot(solid.vertex_point(v)));
      hi = std::max(hi, a.dot(solid.vertex_point(v)));
    }
    std::vector<FootPlane> set;
    for (FaceId f : solid.faces()) {
      const bool concave = concave_round(faces[f.value()], a);
      const bool fillet = concave || rounded(faces[f.value()], a);
      if (!fillet && !tapered(faces[f.value()], a)) continue;
      for (const auto& wire : solid.face_wires(f))
        for (const core::OrientedEdge& oe : wire) {
          const EdgeId e = oe.edge;
          if (solid.edge_is_degenerated(e)) continue;
          // A wall (a chamfer's foot, a countersink's), or a cap within the solid (the
          // floor of a pocket with drafted walls).
          bool foot = false;
          for (FaceId g : solid.edge_faces(e))
            foot = foot ||
                   (g != f && (wall(faces[g.value()], a) || (!fillet && cap(faces[g.value()], a))));
          if (!foot) continue;
          const std::vector<Vec3> p = solid.edge_points_by_length(e, 8);
          double h0 = 1e300, h1 = -1e300;
          for (const Vec3& q : p) h0 = std::min(h0, a.dot(q)), h1 = std::max(h1, a.dot(q));
          if (h1 - h0 > tol || h0 < lo + 1e3 * tol || h0 > hi - 1e3 * tol) continue;
          auto same = std::find_if(set.begin(), set.end(), [&](const FootPlane& q) {
            return std::abs(q.offset - h0) <= 10 * tol;
          });
          if (same != set.end()) {
            same->edges.push_back(e);
            same->concave = same->concave && concave;
          } else {
            set.push_back({a, h0, f, {e}, concave});
          }
        }
    }
    if (!set.empty()) sets.push_back({a, std::move(set), occ::area_across(solid, a)});
  }
  // The axis a user would sweep along first.
  std::stable_sort(sets.begin(), sets.end(),
                   [](const auto& x, const auto& y) { return x.cap_area > y.cap_area; });
  return sets;
}

double turn_across(const occ::Solid& s, const Vec3& m, const Vec3& t, FaceId f, FaceId g) {
  const double eps = 1e-3 * s.diagonal();
  Vec3 into = s.face_normal(f, m).cross(t).normalized();
  if (s.distance_to_face(f, m + eps * into) > s.distance_to_face(f, m - eps * into)) into = -into;
  return into.dot(s.face_normal(g, m));
}

void along_the_solid(const occ::Solid& s, occ::CutCylinder& c) {
  const core::BoundingBox box = s.bounding_box();
  double lo = 1e300, hi = -1e300;
  for (int k = 0; k < 8; ++k) {
    const Vec3 corner((k & 1) ? box.max.x() : box.min.x(), (k & 2) ? box.max.y() : box.min.y(),
                      (k & 4) ? box.max.z() : box.min.z());
    lo = std::min(lo, c.axis.dot(corner - c.origin));
    hi = std::max(hi, c.axis.dot(corner - c.origin));
  }
  c.from = lo - 0.1 * s.diagonal();
  c.to = hi + 0.1 * s.diagonal();
}

namespace {

// Whether faces f and g meet at edge e at a convex angle (more than a degree short of flat,
// seen from inside the solid).
bool convex_edge(const occ::Solid& s, EdgeId e, FaceId f, FaceId g) {
  const std::vector<Vec3> p = s.edge_points_by_length(e, 16);
  return turn_across(s, p[8], (p[9] - p[7]).normalized(), f, g) < -std::sin(M_PI / 180);
}

}  // namespace

std::vector<FootCylinder> foot_cylinders(const occ::Solid& solid) {
  const double tol = 1e-7 * solid.diagonal();
  std::vector<FootCylinder> out;
  for (FaceId f : solid.faces()) {
    const FaceAxis fa = face_axis(solid, f);
    if (!(fa.kind == FaceAxis::torus && !fa.convex) && fa.kind != FaceAxis::cone) continue;
    const core::SurfaceInfo info = solid.surface_info(f);
    auto height = [&](const Vec3& q) { return fa.d.dot(q - info.origin); };
    auto radial = [&](const Vec3& q) { return (q - info.origin) - height(q) * fa.d; };
    // The radius of edge e if it is a whole circle about the axis, else 0.
    auto circle_radius = [&](EdgeId e) {
      if (solid.edge_is_degenerated(e) || solid.edge_first_vertex(e) != solid.edge_last_vertex(e))
        return 0.0;
      const Vec3 start = solid.vertex_point(solid.edge_first_vertex(e));
      const double r = radial(start).norm();
      if (r <= 1e3 * tol) return 0.0;
      for (const Vec3& q : solid.edge_points_by_length(e, 8))
        if (std::abs(height(q) - height(start)) > 10 * tol ||
            std::abs(radial(q).norm() - r) > 10 * tol)
          return 0.0;
      return r;
    };
    int floor_foot = -1;  // in out
    double wall = 0;      // the radius of its foot on a hole's or pocket's wall
    for (const auto& wire : solid.face_wires(f))
      for (const core::OrientedEdge& oe : wire) {
        const EdgeId e = oe.edge;
        const double r = circle_radius(e);
        if (r == 0) continue;
        // On a floor: a planar face across the axis, which it meets tangentially (a fillet) or
        // at a concave edge (a chamfer), not at a convex one (a countersink's rim). On a wall:
        // a cylinder about the axis that does not bulge out (a pocket's, not a boss's).
        bool floor = false;
        for (FaceId g : solid.edge_faces(e)) {
          if (g == f) continue;
          const FaceAxis ga = face_axis(solid, g);
          floor = floor || (cap(ga, fa.d) && !convex_edge(solid, e, f, g));
          if (ga.kind == FaceAxis::cylinder && !ga.convex && std::abs(ga.d.dot(fa.d)) > 1 - 1e-9)
            wall = r;
        }
        if (!floor) continue;
        occ::CutCylinder c;
        c.origin = info.origin;
        c.axis = fa.d;
        c.seam = radial(solid.vertex_point(solid.edge_first_vertex(e))).normalized();
        c.radius = r;
        along_the_solid(solid, c);
        out.push_back({c, f, e});
        floor_foot = int(out.size()) - 1;
      }
    // A fillet or chamfer at a round pocket's floor: the ring between its foot on the floor and
    // a cylinder as far beyond the wall is a solid of revolution (a cut along the wall itself
    // would leave a knife edge where the fillet meets it tangentially); its seam where the
    // floor foot's is.
    if (floor_foot >= 0 && wall > out[floor_foot].surface.radius) {
      FootCylinder ring = out[floor_foot];
      ring.surface.radius = 2 * wall - out[floor_foot].surface.radius;
      ring.ring = true;
      out.push_back(ring);
    }
  }
  return out;
}

}  // namespace vorohex::decompose::detail
