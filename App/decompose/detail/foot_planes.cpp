#include "decompose/detail/foot_planes.h"

#include <algorithm>
#include <cmath>

namespace vorohex::decompose::detail {

using core::EdgeId;
using core::FaceId;
using core::Vec3;

namespace {

// The axis of a plane (its normal) or of a cylinder or cone, unit; zero for other faces.
Vec3 axis_of(const occ::Solid& s, FaceId f) {
  const core::SurfaceInfo info = s.surface_info(f);
  if (info.kind != core::SurfaceKind::plane && info.kind != core::SurfaceKind::cylinder &&
      info.kind != core::SurfaceKind::cone)
    return Vec3::Zero();
  return info.direction.norm() > 0 ? Vec3(info.direction.normalized()) : Vec3::Zero();
}

// Face f parallel to axis a (a wall): a plane whose normal is across it, a cylinder along it.
bool wall(const occ::Solid& s, FaceId f, const Vec3& a) {
  const core::SurfaceInfo info = s.surface_info(f);
  const Vec3 d = axis_of(s, f);
  if (info.kind == core::SurfaceKind::plane) return std::abs(d.dot(a)) < 1e-9;
  if (info.kind == core::SurfaceKind::cylinder) return std::abs(std::abs(d.dot(a)) - 1) < 1e-9;
  return false;
}

// Face f tapered to axis a: a plane neither along nor across it, or a cone about it.
bool tapered(const occ::Solid& s, FaceId f, const Vec3& a) {
  const core::SurfaceInfo info = s.surface_info(f);
  const double c = std::abs(axis_of(s, f).dot(a));
  if (info.kind == core::SurfaceKind::plane) return c > 1e-6 && c < 1 - 1e-6;
  if (info.kind == core::SurfaceKind::cone) return std::abs(c - 1) < 1e-9;
  return false;
}

}  // namespace

std::vector<std::vector<FootPlane>> foot_plane_sets(const occ::Solid& solid) {
  const double tol = 1e-7 * solid.diagonal();
  std::vector<Vec3> axes;
  for (FaceId f : solid.faces()) {
    const core::SurfaceInfo info = solid.surface_info(f);
    if (info.kind != core::SurfaceKind::plane && info.kind != core::SurfaceKind::cylinder) continue;
    const Vec3 d = axis_of(solid, f);
    if (d.norm() == 0) continue;
    bool known = false;
    for (const Vec3& o : axes) known = known || std::abs(o.dot(d)) > 1 - 1e-9;
    if (!known) axes.push_back(d);
  }
  std::vector<std::vector<FootPlane>> sets;
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
    if (!set.empty()) sets.push_back(std::move(set));
  }
  std::stable_sort(sets.begin(), sets.end(),
                   [](const auto& x, const auto& y) { return x.size() < y.size(); });
  return sets;
}

}  // namespace vorohex::decompose::detail
