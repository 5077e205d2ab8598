#include "decompose/detail/foot_planes.h"

#include <algorithm>
#include <cmath>

namespace vorohex::decompose::detail {

using core::EdgeId;
using core::FaceId;
using core::Vec3;

namespace {

// The axis of a planar face (its normal: a plane, or a B-spline that is flat, as lofts
// leave them) or of a cylinder or cone, unit; zero for other faces.
Vec3 axis_of(const occ::Solid& s, FaceId f) {
  if (s.face_is_planar(f)) {
    const auto wires = s.face_wires(f);
    if (wires.empty() || wires[0].empty()) return Vec3::Zero();
    const Vec3 n = s.face_normal(f, s.vertex_point(s.edge_first_vertex(wires[0][0].edge)));
    return n.norm() > 0 ? Vec3(n.normalized()) : Vec3::Zero();
  }
  const core::SurfaceInfo info = s.surface_info(f);
  if (info.kind != core::SurfaceKind::cylinder && info.kind != core::SurfaceKind::cone)
    return Vec3::Zero();
  return info.direction.norm() > 0 ? Vec3(info.direction.normalized()) : Vec3::Zero();
}

// Face f parallel to axis a (a wall): a planar face whose normal is across it, a cylinder
// along it.
bool wall(const occ::Solid& s, FaceId f, const Vec3& a) {
  const Vec3 d = axis_of(s, f);
  if (d.norm() == 0) return false;
  if (s.face_is_planar(f)) return std::abs(d.dot(a)) < 1e-9;
  return s.surface_info(f).kind == core::SurfaceKind::cylinder &&
         std::abs(std::abs(d.dot(a)) - 1) < 1e-9;
}

// Face f tapered to axis a: a planar face neither along nor across it, or a cone about it.
bool tapered(const occ::Solid& s, FaceId f, const Vec3& a) {
  const Vec3 d = axis_of(s, f);
  if (d.norm() == 0) return false;
  const double c = std::abs(d.dot(a));
  if (s.face_is_planar(f)) return c > 1e-6 && c < 1 - 1e-6;
  return s.surface_info(f).kind == core::SurfaceKind::cone && std::abs(c - 1) < 1e-9;
}

}  // namespace

std::vector<FootPlaneSet> foot_plane_sets(const occ::Solid& solid) {
  const double tol = 1e-7 * solid.diagonal();
  std::vector<Vec3> axes;
  for (FaceId f : solid.faces()) {
    if (!solid.face_is_planar(f) && solid.surface_info(f).kind != core::SurfaceKind::cylinder)
      continue;
    const Vec3 d = axis_of(solid, f);
    if (d.norm() == 0) continue;
    bool known = false;
    for (const Vec3& o : axes) known = known || std::abs(o.dot(d)) > 1 - 1e-9;
    if (!known) axes.push_back(d);
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
      if (!tapered(solid, f, a)) continue;
      for (const auto& wire : solid.face_wires(f))
        for (const core::OrientedEdge& oe : wire) {
          const EdgeId e = oe.edge;
          if (solid.edge_is_degenerated(e)) continue;
          bool on_wall = false;
          for (FaceId g : solid.edge_faces(e)) on_wall = on_wall || (g != f && wall(solid, g, a));
          if (!on_wall) continue;
          const std::vector<Vec3> p = solid.edge_points_by_length(e, 8);
          double h0 = 1e300, h1 = -1e300;
          for (const Vec3& q : p) h0 = std::min(h0, a.dot(q)), h1 = std::max(h1, a.dot(q));
          if (h1 - h0 > tol || h0 < lo + 1e3 * tol || h0 > hi - 1e3 * tol) continue;
          auto same = std::find_if(set.begin(), set.end(), [&](const FootPlane& q) {
            return std::abs(q.offset - h0) <= 10 * tol;
          });
          if (same != set.end()) {
            same->edges.push_back(e);
          } else {
            set.push_back({a, h0, f, {e}});
          }
        }
    }
    if (set.empty()) continue;
    // The area of the planar faces across a: the axis a user would sweep along first.
    double caps = 0;
    for (FaceId f : solid.faces())
      if (solid.face_is_planar(f) && std::abs(std::abs(axis_of(solid, f).dot(a)) - 1) < 1e-9)
        caps += solid.area(f);
    sets.push_back({a, std::move(set), caps});
  }
  std::stable_sort(sets.begin(), sets.end(),
                   [](const auto& x, const auto& y) { return x.cap_area > y.cap_area; });
  return sets;
}

}  // namespace vorohex::decompose::detail
