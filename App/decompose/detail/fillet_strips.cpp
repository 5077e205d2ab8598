#include "decompose/detail/fillet_strips.h"

#include <algorithm>
#include <cmath>

namespace vorohex::decompose::detail {

using core::EdgeId;
using core::FaceId;
using core::Vec3;

namespace {

// One side of a fillet: the straight edge along its axis where it touches planar face
// `plane` tangentially, a point of that edge, and the plane's unit normal.
struct Tangent {
  EdgeId edge;
  FaceId plane;
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
};

// A concave cylindrical fillet between two planar faces (its axis outside the solid, the
// planes tangent to it along two lines parallel to its axis).
struct Fillet {
  FaceId face;
  Vec3 axis = Vec3::Zero();  // unit
  double radius = 0;
  Tangent side[2];
};

bool parallel(const Vec3& a, const Vec3& b, double tol = 1e-6) {
  return std::abs(a.normalized().dot(b.normalized())) > 1 - tol;
}

bool fillet_of(const occ::Solid& s, FaceId f, Fillet& out) {
  const core::SurfaceInfo info = s.surface_info(f);
  if (info.kind != core::SurfaceKind::cylinder || info.direction.norm() == 0) return false;
  const auto wires = s.face_wires(f);
  if (wires.size() != 1 || wires[0].size() != 4) return false;
  out.face = f;
  out.axis = info.direction.normalized();
  out.radius = info.radius;
  int found = 0;
  for (const core::OrientedEdge& oe : wires[0]) {
    const core::CurveInfo c = s.curve_info(oe.edge);
    if (c.kind != core::CurveKind::line || !parallel(c.direction, out.axis)) continue;
    if (found == 2) return false;
    FaceId plane;
    for (FaceId g : s.edge_faces(oe.edge))
      if (g != f) plane = g;
    if (!plane.valid() || !s.face_is_planar(plane)) return false;
    const std::vector<Vec3> p = s.edge_points_by_length(oe.edge, 2);
    const Vec3 m = p[1];
    Vec3 radial = (m - info.origin) - out.axis * out.axis.dot(m - info.origin);
    const Vec3 n = s.face_normal(plane, m);
    if (radial.norm() == 0 || n.norm() == 0 || !parallel(radial, n)) return false;  // not tangent
    // Concave: the solid's outward normal on the fillet points to its axis.
    if (s.face_normal(f, m).dot(radial) >= 0) return false;
    out.side[found++] = {oe.edge, plane, m, n.normalized()};
  }
  return found == 2;
}

// Whether two faces share an edge.
bool touch(const occ::Solid& s, FaceId a, FaceId b) {
  for (const auto& w : s.face_wires(a))
    for (const core::OrientedEdge& oe : w)
      for (FaceId g : s.edge_faces(oe.edge))
        if (g == b) return true;
  return false;
}

// The edge two faces share (invalid if none).
EdgeId common_edge(const occ::Solid& s, FaceId a, FaceId b) {
  for (const auto& w : s.face_wires(a))
    for (const core::OrientedEdge& oe : w)
      for (FaceId g : s.edge_faces(oe.edge))
        if (g == b) return oe.edge;
  return EdgeId();
}

// Where lines p + s u and q + t v of one plane cross (false when parallel).
bool cross(const Vec3& p, const Vec3& u, const Vec3& q, const Vec3& v, Vec3& at) {
  const Vec3 w = u.cross(v);
  if (w.norm() < 1e-9) return false;
  const double s = (q - p).cross(v).dot(w) / w.squaredNorm();
  at = p + s * u;
  return true;
}

}  // namespace

FilletStrips fillet_strips(const occ::Solid& solid) {
  FilletStrips out;
  std::vector<Fillet> fillets;
  for (FaceId f : solid.faces()) {
    Fillet fl;
    if (fillet_of(solid, f, fl)) fillets.push_back(fl);
  }
  const core::BoundingBox box = solid.bounding_box();
  const double tol = 1e-7 * solid.diagonal();
  std::vector<char> strip(fillets.size(), 0);
  std::vector<int> floor_side(fillets.size(), -1);
  std::vector<StripPlane> mitres;
  for (std::size_t i = 0; i < fillets.size(); ++i)
    for (std::size_t j = i + 1; j < fillets.size(); ++j) {
      const Fillet &a = fillets[i], &b = fillets[j];
      if (!touch(solid, a.face, b.face) || parallel(a.axis, b.axis) ||
          std::abs(a.radius - b.radius) > 1e3 * tol)
        continue;
      // The floor: the planar face both are tangent to; the walls at right angles to it.
      int fa = -1, fb = -1;
      for (int x = 0; x < 2; ++x)
        for (int y = 0; y < 2; ++y)
          if (a.side[x].plane == b.side[y].plane) fa = x, fb = y;
      if (fa < 0) continue;
      const Tangent &floor_a = a.side[fa], &wall_a = a.side[1 - fa];
      const Tangent &floor_b = b.side[fb], &wall_b = b.side[1 - fb];
      const Vec3 n = floor_a.normal;
      if (std::abs(wall_a.normal.dot(n)) > 1e-6 || std::abs(wall_b.normal.dot(n)) > 1e-6) continue;
      if ((floor_side[i] >= 0 && floor_side[i] != fa) ||
          (floor_side[j] >= 0 && floor_side[j] != fb))
        continue;  // a fillet with two floors: not a pocket's or a boss's
      // In the floor's plane: the feet, and the lines as far beyond the walls.
      auto on_floor = [&](const Vec3& p) { return p - n * n.dot(p - floor_a.point); };
      const Vec3 far_a = 2 * on_floor(wall_a.point) - floor_a.point;
      const Vec3 far_b = 2 * on_floor(wall_b.point) - floor_b.point;
      Vec3 inner, outer;
      if (!cross(floor_a.point, a.axis, floor_b.point, b.axis, inner) ||
          !cross(far_a, a.axis, far_b, b.axis, outer) || (outer - inner).norm() <= 1e3 * tol)
        continue;
      // Along the floor's normal, a tenth of the diagonal beyond the solid's extent.
      double lo = 1e300, hi = -1e300;
      for (int c = 0; c < 8; ++c) {
        const Vec3 corner((c & 1) ? box.max.x() : box.min.x(), (c & 2) ? box.max.y() : box.min.y(),
                          (c & 4) ? box.max.z() : box.min.z());
        lo = std::min(lo, n.dot(corner - inner)), hi = std::max(hi, n.dot(corner - inner));
      }
      lo -= 0.1 * solid.diagonal(), hi += 0.1 * solid.diagonal();
      StripPlane m;
      m.normal = (outer - inner).cross(n).normalized();
      m.offset = m.normal.dot(inner);
      m.face = a.face;
      const EdgeId e = common_edge(solid, a.face, b.face);
      if (e.valid()) m.edges = {e};
      m.kind = StripPlane::mitre;
      m.quad = {inner + lo * n, outer + lo * n, outer + hi * n, inner + hi * n};
      mitres.push_back(m);
      strip[i] = strip[j] = 1;
      floor_side[i] = fa, floor_side[j] = fb;
    }
  for (std::size_t i = 0; i < fillets.size(); ++i) {
    if (!strip[i]) continue;
    const Fillet& f = fillets[i];
    out.fillets.push_back(f.face);
    const Tangent &floor = f.side[floor_side[i]], &wall = f.side[1 - floor_side[i]];
    // Across the floor at the foot (through the axis), and as far beyond the wall.
    const Vec3 normal = floor.normal.cross(f.axis).normalized();
    const double foot = normal.dot(floor.point), at_wall = normal.dot(wall.point);
    out.planes.push_back({normal, foot, f.face, {floor.edge}, StripPlane::across, {}});
    out.planes.push_back({normal, 2 * at_wall - foot, f.face, {wall.edge}, StripPlane::beyond, {}});
    for (FaceId g : {floor.plane, wall.plane})
      if (std::find(out.tangent_faces.begin(), out.tangent_faces.end(), g) ==
          out.tangent_faces.end())
        out.tangent_faces.push_back(g);
  }
  out.planes.insert(out.planes.end(), mitres.begin(), mitres.end());
  return out;
}

}  // namespace vorohex::decompose::detail
