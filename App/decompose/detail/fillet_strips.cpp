#include "decompose/detail/fillet_strips.h"

#include "decompose/detail/foot_planes.h"

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

// A floor fillet's rounded corner: a surface of revolution (or a torus) about an axis along
// the floor's normal, tangent to the floor along an arc of radius `foot` about it and to a
// coaxial wall cylinder along an arc of radius `wall`, between two straight fillets (its two
// other edges, each in a plane through the axis: `end` the direction of that plane from it).
struct Corner {
  FaceId face, floor, wall_face;
  Vec3 origin = Vec3::Zero(), axis = Vec3::Zero();
  double foot = 0, wall = 0;
  EdgeId foot_edge, wall_edge;
  int fillet[2] = {-1, -1};  // in the fillets found
  EdgeId profile[2];
  Vec3 end[2];
};

bool corner_of(const occ::Solid& s, FaceId f, const std::vector<Fillet>& fillets, Corner& out) {
  const core::SurfaceInfo info = s.surface_info(f);
  if ((info.kind != core::SurfaceKind::torus && info.kind != core::SurfaceKind::revolution) ||
      info.direction.norm() == 0)
    return false;
  const auto wires = s.face_wires(f);
  if (wires.size() != 1 || wires[0].size() != 4) return false;
  out.face = f;
  out.axis = info.direction.normalized();
  out.origin = info.origin;
  const double tol = 1e-6 * s.diagonal();
  auto off_axis = [&](const Vec3& p) {
    const Vec3 d = p - out.origin;
    return Vec3(d - out.axis * out.axis.dot(d));
  };
  int ends = 0;
  for (const core::OrientedEdge& oe : wires[0]) {
    FaceId g;
    for (FaceId h : s.edge_faces(oe.edge))
      if (h != f) g = h;
    if (!g.valid()) return false;
    const core::CurveInfo c = s.curve_info(oe.edge);
    const bool about_axis = c.kind == core::CurveKind::circle && parallel(c.direction, out.axis) &&
                            off_axis(c.origin).norm() <= tol;
    const core::SurfaceInfo gi = s.surface_info(g);
    if (about_axis && s.face_is_planar(g)) {
      out.floor = g, out.foot = c.radius, out.foot_edge = oe.edge;
    } else if (about_axis && gi.kind == core::SurfaceKind::cylinder &&
               parallel(gi.direction, out.axis) && off_axis(gi.origin).norm() <= tol) {
      out.wall_face = g, out.wall = c.radius, out.wall_edge = oe.edge;
    } else {
      int k = -1;
      for (std::size_t i = 0; i < fillets.size(); ++i)
        if (fillets[i].face == g) k = int(i);
      if (k < 0 || ends == 2) return false;
      const std::vector<Vec3> p = s.edge_points_by_length(oe.edge, 2);
      const Vec3 r = off_axis(p[1]);
      if (r.norm() <= tol) return false;
      out.fillet[ends] = k, out.profile[ends] = oe.edge, out.end[ends] = r.normalized();
      ++ends;
    }
  }
  return ends == 2 && out.floor.valid() && out.wall_face.valid() && out.foot > 0 &&
         std::abs(out.wall - out.foot) > tol && 2 * out.wall - out.foot > tol;
}

// How far beyond its wall a fillet's strip ends, as a multiple of how far its foot is in
// front of it (1: as far): where an edge of the solid along the fillet's axis lies behind the
// wall between a quarter and one and a half times that far, along the fillet's length (a
// boss whose top edges are filleted too: the top fillet's foot on its top face), the strip
// ends there instead - a plane as far would leave a sliver of the top face between it and
// the top fillet, on which the strip's sweep folded.
double beyond_factor(const occ::Solid& s, const Fillet& f, const Tangent& floor,
                     const Tangent& wall) {
  const Vec3 normal = floor.normal.cross(f.axis).normalized();
  const double at_wall = normal.dot(wall.point), ahead = at_wall - normal.dot(floor.point);
  if (ahead == 0) return 1;
  const std::vector<Vec3> own = s.edge_points_by_length(floor.edge, 2);
  const double from = std::min(f.axis.dot(own[0]), f.axis.dot(own[2]));
  const double to = std::max(f.axis.dot(own[0]), f.axis.dot(own[2]));
  double best = 0;  // none found
  for (EdgeId e : s.edges()) {
    const core::CurveInfo c = s.curve_info(e);
    if (c.kind != core::CurveKind::line || !parallel(c.direction, f.axis)) continue;
    const std::vector<Vec3> p = s.edge_points_by_length(e, 2);
    // Not on a face the plane would run along (a plate's side as far beyond a pocket's wall:
    // its pieces would end in slivers there).
    bool along_a_face = false;
    for (FaceId g : s.edge_faces(e))
      along_a_face =
          along_a_face || (s.face_is_planar(g) && parallel(s.face_normal(g, p[1]), normal));
    if (along_a_face) continue;
    const double lo = std::min(f.axis.dot(p[0]), f.axis.dot(p[2]));
    const double hi = std::max(f.axis.dot(p[0]), f.axis.dot(p[2]));
    if (hi <= from || lo >= to) continue;
    const double k = (normal.dot(p[1]) - at_wall) / ahead;
    if (k >= 0.25 && k <= 1.5 && (best == 0 || std::abs(k - 1) < std::abs(best - 1))) best = k;
  }
  return best > 0 ? best : 1;
}

// The quad over segment a-b across the whole solid along unit n (a tenth of its diagonal
// beyond its extent): a bounded cut's tool.
std::vector<Vec3> column(const occ::Solid& solid, const Vec3& a, const Vec3& b, const Vec3& n) {
  const core::BoundingBox box = solid.bounding_box();
  double lo = 1e300, hi = -1e300;
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner((c & 1) ? box.max.x() : box.min.x(), (c & 2) ? box.max.y() : box.min.y(),
                      (c & 4) ? box.max.z() : box.min.z());
    lo = std::min(lo, n.dot(corner - a)), hi = std::max(hi, n.dot(corner - a));
  }
  lo -= 0.1 * solid.diagonal(), hi += 0.1 * solid.diagonal();
  return {a + lo * n, b + lo * n, b + hi * n, a + hi * n};
}

}  // namespace

FilletStrips fillet_strips(const occ::Solid& solid) {
  FilletStrips out;
  std::vector<Fillet> fillets;
  for (FaceId f : solid.faces()) {
    Fillet fl;
    if (fillet_of(solid, f, fl)) fillets.push_back(fl);
  }
  const double tol = 1e-7 * solid.diagonal();
  std::vector<char> strip(fillets.size(), 0);
  std::vector<int> floor_side(fillets.size(), -1);
  // Each strip's beyond_factor, found once (a fillet has one floor: its mitres and its planes
  // ask for the same).
  std::vector<double> factor(fillets.size(), 0);
  auto beyond_of = [&](std::size_t i, const Tangent& floor, const Tangent& wall) {
    if (factor[i] == 0) factor[i] = beyond_factor(solid, fillets[i], floor, wall);
    return factor[i];
  };
  std::vector<StripPlane> mitres;
  for (std::size_t i = 0; i < fillets.size(); ++i)
    for (std::size_t j = i + 1; j < fillets.size(); ++j) {
      const Fillet &a = fillets[i], &b = fillets[j];
      const EdgeId mitre = common_edge(solid, a.face, b.face);
      if (!mitre.valid() || parallel(a.axis, b.axis) || std::abs(a.radius - b.radius) > 1e3 * tol)
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
      const Vec3 far_a = on_floor(wall_a.point) +
                         beyond_of(i, floor_a, wall_a) * (on_floor(wall_a.point) - floor_a.point);
      const Vec3 far_b = on_floor(wall_b.point) +
                         beyond_of(j, floor_b, wall_b) * (on_floor(wall_b.point) - floor_b.point);
      Vec3 inner, outer;
      if (!cross(floor_a.point, a.axis, floor_b.point, b.axis, inner) ||
          !cross(far_a, a.axis, far_b, b.axis, outer) || (outer - inner).norm() <= 1e3 * tol)
        continue;
      StripPlane m;
      m.normal = (outer - inner).cross(n).normalized();
      m.offset = m.normal.dot(inner);
      m.face = a.face;
      m.edges = {mitre};
      m.kind = StripPlane::mitre;
      m.quad = column(solid, inner, outer, n);
      mitres.push_back(m);
      strip[i] = strip[j] = 1;
      floor_side[i] = fa, floor_side[j] = fb;
    }
  // Rounded corners between straight fillets on one floor (none of them at a mitre).
  std::vector<Corner> corners;
  for (FaceId f : solid.faces()) {
    Corner c;
    if (!corner_of(solid, f, fillets, c)) continue;
    bool fits = true;
    for (int k : c.fillet) {
      const Fillet& fl = fillets[std::size_t(k)];
      fits = fits && !strip[std::size_t(k)] &&
             (fl.side[0].plane == c.floor || fl.side[1].plane == c.floor) &&
             std::abs(fl.radius - std::abs(c.wall - c.foot)) <= 1e3 * tol;
    }
    if (fits) corners.push_back(c);
  }
  std::vector<int> corners_of(fillets.size(), 0);
  for (const Corner& c : corners)
    for (int k : c.fillet) ++corners_of[std::size_t(k)];
  for (std::size_t i = 0; i < fillets.size(); ++i) {
    if (strip[i] || corners_of[i] != 2) continue;
    const Fillet& f = fillets[i];
    Corner const* c0 = nullptr;
    for (const Corner& c : corners)
      if (c.fillet[0] == int(i) || c.fillet[1] == int(i)) c0 = &c;
    const int fs = f.side[0].plane == c0->floor ? 0 : 1;
    const Tangent &floor = f.side[fs], &wall = f.side[1 - fs];
    const Vec3 n = floor.normal;
    const Vec3 normal = n.cross(f.axis).normalized();
    const Vec3 a = solid.vertex_point(solid.edge_first_vertex(floor.edge));
    const Vec3 b = solid.vertex_point(solid.edge_last_vertex(floor.edge));
    const double shift = 2 * normal.dot(wall.point - floor.point);  // to the far plane
    out.fillets.push_back(f.face);
    out.planes.push_back(
        {normal, normal.dot(a), f.face, {floor.edge}, StripPlane::across, column(solid, a, b, n)});
    out.planes.push_back({normal,
                          normal.dot(a) + shift,
                          f.face,
                          {wall.edge},
                          StripPlane::beyond,
                          column(solid, a + shift * normal, b + shift * normal, n)});
    for (FaceId g : {floor.plane, wall.plane})
      if (std::find(out.tangent_faces.begin(), out.tangent_faces.end(), g) ==
          out.tangent_faces.end())
        out.tangent_faces.push_back(g);
  }
  for (const Corner& c : corners) {
    if (corners_of[std::size_t(c.fillet[0])] != 2 || corners_of[std::size_t(c.fillet[1])] != 2)
      continue;
    // The sector from one straight strip's end to the other's, turning right-handed about
    // the axis.
    Vec3 from = c.end[0], to = c.end[1];
    if (from.cross(to).dot(c.axis) < 0) std::swap(from, to);
    const double angle = std::atan2(from.cross(to).dot(c.axis), from.dot(to));
    const double far = 2 * c.wall - c.foot;
    for (bool beyond : {false, true}) {
      occ::CutCylinder cyl;
      cyl.origin = c.origin, cyl.axis = c.axis, cyl.seam = from, cyl.angle = angle;
      cyl.radius = beyond ? far : c.foot;
      along_the_solid(solid, cyl);
      out.cylinders.push_back({cyl, c.face, beyond ? c.wall_edge : c.foot_edge, beyond});
    }
    for (int e = 0; e < 2; ++e) {
      const Vec3 inner = c.origin + c.foot * c.end[e], outer = c.origin + far * c.end[e];
      const Vec3 normal = c.end[e].cross(c.axis).normalized();
      out.planes.push_back({normal,
                            normal.dot(inner),
                            c.face,
                            {c.profile[e]},
                            StripPlane::corner,
                            column(solid, inner, outer, c.axis)});
    }
    out.fillets.push_back(c.face);
    out.fillets.push_back(c.wall_face);
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
    const double beyond = at_wall + beyond_of(i, floor, wall) * (at_wall - foot);
    out.planes.push_back({normal, beyond, f.face, {wall.edge}, StripPlane::beyond, {}});
    for (FaceId g : {floor.plane, wall.plane})
      if (std::find(out.tangent_faces.begin(), out.tangent_faces.end(), g) ==
          out.tangent_faces.end())
        out.tangent_faces.push_back(g);
  }
  out.planes.insert(out.planes.end(), mitres.begin(), mitres.end());
  return out;
}

}  // namespace vorohex::decompose::detail
