#include "decompose/detail/cut_surfaces.h"

#include <algorithm>
#include <cmath>

#include "decompose/detail/foot_planes.h"

namespace vorohex::decompose::detail {

using core::EdgeId;
using core::FaceId;
using core::Vec3;

namespace {

// A planar face of the solid that touches cylinder c tangently along a line (HexMe i14: a
// lug as wide as the tube it stands on, its sides tangent to the tube); its unit normal in
// `n`. Cut along the cylinder, the piece beyond it would come to an edge of zero angle
// there.
bool tangent_planar_face(const occ::Solid& s, const occ::CutCylinder& c, Vec3& n) {
  const double tol = 1e-6 * s.diagonal();
  for (FaceId f : s.faces()) {
    if (!s.face_is_planar(f)) continue;
    const core::SurfaceInfo info = s.surface_info(f);
    if (info.kind != core::SurfaceKind::plane) continue;
    const Vec3 fn = info.direction.normalized();
    if (std::abs(fn.dot(c.axis)) > 1e-9) continue;
    const double d = fn.dot(c.origin - info.origin);  // the axis's distance from the plane
    if (std::abs(std::abs(d) - c.radius) > tol) continue;
    // The line of contact, sampled over the face's extent along the axis.
    const Vec3 q = c.origin - d * fn;
    const core::BoundingBox box = s.face_bounding_box(f);
    double lo = 0, hi = 0;
    for (int k = 0; k < 8; ++k) {
      const Vec3 corner((k & 1) ? box.max.x() : box.min.x(), (k & 2) ? box.max.y() : box.min.y(),
                        (k & 4) ? box.max.z() : box.min.z());
      const double t = (corner - q).dot(c.axis);
      lo = k ? std::min(lo, t) : t;
      hi = k ? std::max(hi, t) : t;
    }
    for (int k = 1; k < 8; ++k)
      if (s.distance_to_face(f, q + (lo + (hi - lo) * k / 8.0) * c.axis) <= tol) {
        n = fn;
        return true;
      }
  }
  return false;
}

// A square on the plane covering the solid (its tool face for the splitter).
std::vector<Vec3> covering_square(const occ::Solid& s, const Plane& pl) {
  const core::BoundingBox box = s.bounding_box();
  const Vec3 centre = 0.5 * (box.min + box.max);
  const Vec3 c = centre - (pl.normal.dot(centre) - pl.offset) * pl.normal;
  const Vec3 any = std::abs(pl.normal.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  const Vec3 u = pl.normal.cross(any).normalized(), v = pl.normal.cross(u);
  const double h = 2 * s.diagonal();
  return {c - h * u - h * v, c + h * u - h * v, c + h * u + h * v, c - h * u + h * v};
}

}  // namespace

// The same cylinder (axis line and radius within `tol`).
bool same_cylinder(const occ::CutCylinder& a, const occ::CutCylinder& b, double tol) {
  if (std::abs(a.axis.dot(b.axis)) < 1 - 1e-9 || std::abs(a.radius - b.radius) > tol) return false;
  const Vec3 d = b.origin - a.origin;
  return (d - d.dot(a.axis) * a.axis).norm() <= tol;
}

// Adds `pl` to `planes` unless it is there (same plane within tol: its edges join it).
void add_plane(std::vector<Plane>& planes, Plane pl, double tol) {
  if (!pl.quad.empty()) {  // bounded: a tool of its own
    planes.push_back(std::move(pl));
    return;
  }
  if (pl.normal.x() + 1e-12 * pl.normal.y() + 1e-24 * pl.normal.z() < 0)
    pl.normal = -pl.normal, pl.offset = -pl.offset;
  for (Plane& q : planes)
    if (q.quad.empty() && q.normal.dot(pl.normal) > 1 - 1e-9 &&
        std::abs(q.offset - pl.offset) <= tol) {
      q.edges.insert(q.edges.end(), pl.edges.begin(), pl.edges.end());
      return;
    }
  planes.push_back(std::move(pl));
}

// The surfaces of the faces at concave edges: planes, and cylinders (a post of round
// section on a plate, a round boss); false (with why) when a concave edge has a face of
// another kind (no exact surface to cut along).
bool concave_surfaces(const occ::Solid& s, std::vector<Plane>& planes,
                      std::vector<Cylinder>& cylinders, std::string& why) {
  const double tol = 1e-7 * s.diagonal();
  for (EdgeId e : s.edges()) {
    if (s.edge_is_degenerated(e)) continue;
    const std::vector<FaceId> faces = s.edge_faces(e);
    if (faces.size() != 2) continue;
    // The middle and the tangent there (a chord around it: a closed edge such as a
    // circle starts and ends at one point).
    const std::vector<Vec3> p = s.edge_points_by_length(e, 16);
    const Vec3 m = p[8];
    const Vec3 t = (p[9] - p[7]).normalized();
    if (detail::turn_across(s, m, t, faces[0], faces[1]) <= std::sin(M_PI / 180))
      continue;  // convex or smooth
    // What each face gives to cut along: its plane, or its cylinder. A concave edge needs
    // one cut, so a face of another kind (a cone, a torus, a B-spline) is left out when the
    // other face gives one.
    bool planar[2], round[2];
    occ::CutCylinder cyl[2];
    for (int k = 0; k < 2; ++k) {
      planar[k] = s.face_is_planar(faces[k]);
      round[k] = !planar[k] && occ::face_cylinder(s, faces[k], &cyl[k]);
    }
    if (!planar[0] && !round[0] && !planar[1] && !round[1]) {
      why = "its concave " + core::entity_name(e) + " lies between the curved " +
            core::entity_name(faces[0]) + " and " + core::entity_name(faces[1]) +
            " (neither a plane nor a cylinder to cut along)";
      return false;
    }
    for (int k = 0; k < 2; ++k) {
      if (round[k]) {
        detail::along_the_solid(s, cyl[k]);
        bool known = false;
        for (Cylinder& c : cylinders)
          if (!known && same_cylinder(c.surface, cyl[k], tol)) known = true, c.edges.push_back(e);
        if (!known) cylinders.push_back({cyl[k], faces[k], {e}});
        continue;
      }
      if (!planar[k]) continue;
      const Vec3 n = s.face_normal(faces[k], m);
      add_plane(planes, {n, n.dot(m), faces[k], {e}}, tol);
    }
  }
  return true;
}

// Each cylinder a planar face touches tangently is replaced by the planes tangent to it at
// right angles to that face, on the sides where its concave edges are (a lug on a tube: the
// plane across the tube's top, above which the lug is a plain sweep). False when none is.
bool tangent_planes_instead(const occ::Solid& s, std::vector<Plane>& planes,
                            std::vector<Cylinder>& cylinders) {
  const double tol = 1e-7 * s.diagonal();
  bool replaced = false;
  std::vector<Cylinder> kept;
  for (Cylinder& c : cylinders) {
    Vec3 n;
    if (!tangent_planar_face(s, c.surface, n)) {
      kept.push_back(std::move(c));
      continue;
    }
    const Vec3 m = c.surface.axis.cross(n).normalized();
    bool side[2] = {false, false};  // the concave edges beyond +m, beyond -m
    for (EdgeId e : c.edges) {
      const double h = m.dot(s.edge_points_by_length(e, 2)[1] - c.surface.origin);
      if (std::abs(h) > 0.05 * c.surface.radius) side[h < 0] = true;
    }
    if (!side[0] && !side[1]) {
      kept.push_back(std::move(c));
      continue;
    }
    for (int k = 0; k < 2; ++k)
      if (side[k]) {
        const Vec3 mk = k ? Vec3(-m) : m;
        add_plane(planes, {mk, mk.dot(c.surface.origin) + c.surface.radius, c.face, c.edges, true},
                  tol);
      }
    replaced = true;
  }
  cylinders = std::move(kept);
  return replaced;
}

bool drop_oblique_planes(const occ::Solid& s, std::vector<Plane>& planes,
                         const std::vector<Cylinder>& cylinders) {
  // The part's axes from its planar faces, largest first.
  std::vector<std::pair<double, Vec3>> faces;
  for (FaceId f : s.faces()) {
    if (!s.face_is_planar(f)) continue;
    const core::SurfaceInfo info = s.surface_info(f);
    if (info.kind == core::SurfaceKind::plane)
      faces.emplace_back(s.area(f), info.direction.normalized());
  }
  std::sort(faces.begin(), faces.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  if (faces.empty()) return false;
  constexpr double kParallel = 1 - 1e-9, kPerpendicular = 1e-9;
  std::vector<Vec3> axes{faces[0].second};
  for (const auto& [area, n] : faces)
    if (std::abs(n.dot(axes[0])) < kPerpendicular) {
      axes.push_back(n);
      axes.push_back(axes[0].cross(n).normalized());
      break;
    }
  if (axes.size() < 3) return false;  // no frame of three axes (a plate whose sides are sloped)
  auto along_an_axis = [&](const Vec3& n) {
    return std::any_of(axes.begin(), axes.end(),
                       [&](const Vec3& a) { return std::abs(n.dot(a)) > kParallel; });
  };
  auto cut_by_another = [&](core::EdgeId e, std::size_t self) {
    for (std::size_t k = 0; k < planes.size(); ++k)
      if (k != self && std::count(planes[k].edges.begin(), planes[k].edges.end(), e)) return true;
    for (const Cylinder& c : cylinders)
      if (std::count(c.edges.begin(), c.edges.end(), e)) return true;
    return false;
  };
  bool dropped = false;
  for (std::size_t k = 0; k < planes.size();) {
    const Plane& pl = planes[k];
    const bool oblique = !along_an_axis(pl.normal) && !pl.edges.empty() && pl.quad.empty();
    if (oblique && std::all_of(pl.edges.begin(), pl.edges.end(),
                               [&](core::EdgeId e) { return cut_by_another(e, k); })) {
      planes.erase(planes.begin() + std::ptrdiff_t(k));
      dropped = true;
    } else {
      ++k;
    }
  }
  return dropped;
}

// Whether a piece has an edge where its two faces meet at an angle near zero (a knife)
// that is no such edge of the solid: a cut surface tangent to a face of the solid (HexMe
// i14's lug cut off its tube along the tube's cylinder, to which the lug's sides are
// tangent). No hexahedron along such an edge is good; the sweeps' layers fold there.
bool adds_knife_edges(const occ::Solid& solid, const std::vector<occ::Solid>& pieces) {
  const double cos_knife = std::cos(3 * M_PI / 180);
  const double tol = 1e-6 * solid.diagonal();
  auto knife = [&](const occ::Solid& s, EdgeId e, const Vec3& m) {
    const std::vector<FaceId> faces = s.edge_faces(e);
    return faces.size() == 2 &&
           s.face_normal(faces[0], m).dot(s.face_normal(faces[1], m)) < -cos_knife;
  };
  for (const occ::Solid& p : pieces)
    for (EdgeId e : p.edges()) {
      if (p.edge_is_degenerated(e)) continue;
      const Vec3 m = p.edge_points_by_length(e, 2)[1];
      if (!knife(p, e, m)) continue;
      const EdgeId own = solid.nearest_edge(m);
      if ((solid.project_to_edge(own, m) - m).norm() <= tol && knife(solid, own, m)) continue;
      return true;
    }
  return false;
}

std::vector<Vec3> tool_of(const occ::Solid& s, const Plane& pl) {
  return pl.quad.empty() ? covering_square(s, pl) : pl.quad;
}

}  // namespace vorohex::decompose::detail
