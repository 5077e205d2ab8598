#include "decompose/detail/hole_planes.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "occ/split_solid.h"

namespace vorohex::decompose::detail {

using core::FaceId;
using core::Vec3;

namespace {

struct Hole {
  occ::CutCylinder cylinder;
  double area = 0;  // of its faces
  FaceId largest;   // its largest face
  double largest_area = 0;
  core::BoundingBox box;  // of its faces
};

// Any unit vector at right angles to d.
Vec3 perpendicular(const Vec3& d) {
  const Vec3 any = std::abs(d.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  return d.cross(any).normalized();
}

bool parallel(const Vec3& a, const Vec3& b) {
  return std::abs(a.dot(b)) > 1 - 1e-6;
}

// Whether the points (on the cylinder) go all around its axis: no gap of a quarter turn.
bool all_around(const occ::CutCylinder& c, const std::vector<Vec3>& points) {
  const Vec3 u = perpendicular(c.axis), v = c.axis.cross(u);
  std::vector<double> angle;
  for (const Vec3& p : points) {
    const Vec3 r = p - c.origin;
    angle.push_back(std::atan2(r.dot(v), r.dot(u)));
  }
  if (angle.size() < 3) return false;
  std::sort(angle.begin(), angle.end());
  double gap = angle.front() + 2 * M_PI - angle.back();
  for (std::size_t k = 1; k < angle.size(); ++k) gap = std::max(gap, angle[k] - angle[k - 1]);
  return gap < M_PI / 2;
}

std::vector<Hole> holes_of(const occ::Solid& s) {
  const double tol = 1e-7 * s.diagonal();
  std::vector<Hole> holes;
  std::vector<std::vector<Vec3>> points;  // per hole: its faces' edge points
  for (const occ::FaceSample& sample : occ::sample_faces(s)) {
    occ::CutCylinder c;
    if (!occ::face_cylinder(s, sample.face, &c)) continue;
    Vec3 r = sample.point - c.origin;
    r -= r.dot(c.axis) * c.axis;
    if (sample.normal.dot(r) >= 0) continue;  // material inside: a boss, a shaft
    std::size_t k = 0;
    for (; k < holes.size(); ++k) {
      const occ::CutCylinder& h = holes[k].cylinder;
      const Vec3 d = c.origin - h.origin;
      if (parallel(h.axis, c.axis) && std::abs(h.radius - c.radius) <= tol &&
          (d - d.dot(h.axis) * h.axis).norm() <= tol)
        break;
    }
    const core::BoundingBox box = s.face_bounding_box(sample.face);
    if (k == holes.size()) holes.push_back({c, 0, sample.face, 0, box}), points.emplace_back();
    Hole& h = holes[k];
    if (sample.area > h.largest_area) h.largest = sample.face, h.largest_area = sample.area;
    h.area += sample.area;
    h.box.min = h.box.min.cwiseMin(box.min), h.box.max = h.box.max.cwiseMax(box.max);
    for (const auto& wire : s.face_wires(sample.face))
      for (const core::OrientedEdge& e : wire) {
        if (s.edge_is_degenerated(e.edge)) continue;
        const std::vector<Vec3> p = s.edge_points_by_length(e.edge, 12);
        points[k].insert(points[k].end(), p.begin(), p.end());
      }
  }
  std::vector<Hole> round;
  for (std::size_t k = 0; k < holes.size(); ++k)
    if (all_around(holes[k].cylinder, points[k])) round.push_back(holes[k]);
  return round;
}

// The direction across hole axis d the planes are set along: `preferred` where at right
// angles to d, else the normal of the largest planar face at right angles to it (a block's
// side), else any.
Vec3 across(const occ::Solid& s, const Vec3& d, const Vec3* preferred) {
  if (preferred && std::abs(preferred->dot(d)) < 1e-6) return *preferred;
  double best = 0;
  Vec3 n = perpendicular(d);
  for (FaceId f : s.faces()) {
    if (!s.face_is_planar(f)) continue;
    const core::SurfaceInfo info = s.surface_info(f);
    if (info.kind != core::SurfaceKind::plane) continue;
    const Vec3 fn = info.direction.normalized();
    const double a = s.area(f);
    if (std::abs(fn.dot(d)) < 1e-6 && a > best) best = a, n = fn;
  }
  return n;
}

// How far a plane normal . x = offset keeps from an edge sampled at `points`: the distance
// to the edge's extent along the normal, or where it crosses the edge, to the nearer end of
// that extent; halved where that end is a turn of the edge, not one of its ends (crossing a
// boss's circle near its side leaves a sliver of the boss, a piece no scheme takes, where
// passing as near beside it leaves a thin slab; crossing a straight edge near its end is
// only as near as its vertex; a closed edge has no ends).
double clearance(const std::vector<Vec3>& points, const Vec3& normal, double offset) {
  std::size_t lo = 0, hi = 0;
  for (std::size_t k = 1; k < points.size(); ++k) {
    if (normal.dot(points[k]) < normal.dot(points[lo])) lo = k;
    if (normal.dot(points[k]) > normal.dot(points[hi])) hi = k;
  }
  const double a = normal.dot(points[lo]), b = normal.dot(points[hi]);
  if (offset <= a) return a - offset;
  if (offset >= b) return offset - b;
  const bool nearer_lo = offset - a < b - offset;
  const std::size_t end = nearer_lo ? lo : hi;
  const double d = nearer_lo ? offset - a : b - offset;
  const bool closed = (points.front() - points.back()).norm() <= 1e-9 * (b - a);  // a circle
  return !closed && (end == 0 || end + 1 == points.size()) ? d : 0.5 * d;
}

// The pair of planes normal . x = normal . origin +- b around the hole, b = k radius with k
// the first of a few (1.5 first) whose planes keep half a radius clear of every edge of the
// solid (the hole's own too), else the one keeping clearest; none of them where the solid
// does not reach.
void add_pair(const occ::Solid& s, const Hole& h, const Vec3& normal,
              const std::vector<std::vector<Vec3>>& edges, std::vector<HolePlane>& out) {
  const double c = normal.dot(h.cylinder.origin), r = h.cylinder.radius;
  const double factors[] = {1.5, 1.35, 1.7, 1.25, 2.0};
  double best_k = factors[0], best = -1;
  for (double k : factors) {
    double nearest = 1e300;
    for (const std::vector<Vec3>& e : edges)
      nearest =
          std::min({nearest, clearance(e, normal, c + k * r), clearance(e, normal, c - k * r)});
    if (nearest >= 0.5 * r * (1 - 1e-6)) {  // the hole's own edges: exactly at 1.5
      best_k = k;
      break;
    }
    if (nearest > best + 1e-9 * s.diagonal()) best = nearest, best_k = k;
  }
  const core::BoundingBox box = s.bounding_box();
  double lo = 1e300, hi = -1e300;
  for (int k = 0; k < 8; ++k) {
    const Vec3 corner((k & 1) ? box.max.x() : box.min.x(), (k & 2) ? box.max.y() : box.min.y(),
                      (k & 4) ? box.max.z() : box.min.z());
    lo = std::min(lo, normal.dot(corner)), hi = std::max(hi, normal.dot(corner));
  }
  for (double side : {-1.0, 1.0}) {
    const double offset = c + side * best_k * r;
    if (offset > lo && offset < hi) out.push_back({normal, offset, h.largest, h.cylinder});
  }
}

// Whether hole g crosses hole h inside the box the planes around h make (their axes pass
// within the sum of their radii, at a point of both holes' extents) and is narrower than
// that box, so that h's piece would hold g's crossing too (two crossing holes: no sweep
// takes it). A hole wider than the box (a tube's bore, crossed by a hole through its wall)
// takes the box's middle away, leaving pieces of the wall.
bool crosses_inside(const occ::Solid& s, const Hole& h, const Hole& g) {
  const Vec3 &a = h.cylinder.axis, &b = g.cylinder.axis;
  if (parallel(a, b) || g.cylinder.radius >= 1.5 * h.cylinder.radius) return false;
  const Vec3 w = h.cylinder.origin - g.cylinder.origin;
  const double ab = a.dot(b), den = 1 - ab * ab;
  const double t = (ab * b.dot(w) - a.dot(w)) / den, u = (b.dot(w) - ab * a.dot(w)) / den;
  const Vec3 p = h.cylinder.origin + t * a, q = g.cylinder.origin + u * b;
  if ((p - q).norm() >= h.cylinder.radius + g.cylinder.radius) return false;
  const double tol = 1e-6 * s.diagonal();
  auto within = [&](const Hole& k, const Vec3& x) {
    return (x.array() >= k.box.min.array() - tol).all() &&
           (x.array() <= k.box.max.array() + tol).all();
  };
  return within(h, p) && within(g, q);
}

bool same_set(const std::vector<HolePlane>& a, const std::vector<HolePlane>& b, double tol) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (!parallel(a[k].normal, b[k].normal) ||
        std::abs(a[k].offset * a[k].normal.dot(b[k].normal) - b[k].offset) > tol)
      return false;
  return true;
}

}  // namespace

std::vector<std::vector<HolePlane>> hole_plane_sets(const occ::Solid& solid) {
  const std::vector<Hole> holes = holes_of(solid);
  if (holes.empty()) return {};
  std::vector<std::vector<Vec3>> edges;  // each sampled
  for (core::EdgeId e : solid.edges())
    if (!solid.edge_is_degenerated(e)) edges.push_back(solid.edge_points_by_length(e, 16));
  // The directions holes run along, the one with the most hole area first.
  std::vector<std::pair<double, Vec3>> directions;
  for (const Hole& h : holes) {
    auto it = std::find_if(directions.begin(), directions.end(),
                           [&](const auto& d) { return parallel(d.second, h.cylinder.axis); });
    if (it == directions.end())
      directions.push_back({h.area, h.cylinder.axis});
    else
      it->first += h.area;
  }
  std::stable_sort(directions.begin(), directions.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<std::vector<HolePlane>> sets;
  auto add_set = [&](const Vec3* along) {
    std::vector<HolePlane> set;
    for (const Hole& h : holes) {
      if (along && parallel(*along, h.cylinder.axis)) continue;
      for (const Hole& g : holes)
        if (&g != &h && crosses_inside(solid, h, g)) return;  // no set: its piece would not sweep
      const Vec3 e1 = across(solid, h.cylinder.axis, along);
      const Vec3 e2 = h.cylinder.axis.cross(e1).normalized();
      add_pair(solid, h, e1, edges, set);
      add_pair(solid, h, e2, edges, set);
    }
    if (set.empty()) return;
    for (const auto& known : sets)
      if (same_set(known, set, 1e-7 * solid.diagonal())) return;
    sets.push_back(std::move(set));
  };
  for (const auto& d : directions) add_set(&d.second);
  add_set(nullptr);
  return sets;
}

}  // namespace vorohex::decompose::detail
