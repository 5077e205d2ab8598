#include "voronoi/detail/distance_field.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace vorohex::voronoi::detail {
namespace {

using model::EntityKind;
using model::EntityRef;

double box_distance2(const Vec3& lo, const Vec3& hi, const Vec3& p) {
  const Vec3 d = (lo - p).cwiseMax(p - hi).cwiseMax(0.0);
  return d.squaredNorm();
}

// The entity that owns points nearest to a governing primitive of `origin`.
int owning_entity(const model::BRepModel& m, EntityRef origin) {
  if (m.governs_interior(origin)) return m.index(origin);
  if (origin.kind == EntityKind::edge) {
    const auto& faces = m.edge(core::EdgeId(origin.id)).faces;
    if (!faces.empty()) return m.index(model::ref(faces.front()));
  }
  if (origin.kind == EntityKind::vertex) {
    const auto& faces = m.vertex(core::VertexId(origin.id)).faces;
    if (!faces.empty()) return m.index(model::ref(faces.front()));
  }
  return m.index(origin);
}

}  // namespace

DistanceField::DistanceField(const model::BRepModel& model) : model_(model) {
  const model::Linearization& lin = model.linear();
  tie_ = 1e-9 * std::max(model.diagonal(), 1e-300);
  entity_prims_.resize(model.num_entities());
  auto add = [&](Prim p, bool governs, const std::vector<Vec3>& pts) {
    p.lo = p.hi = pts.front();
    for (const Vec3& q : pts) {
      p.lo = p.lo.cwiseMin(q);
      p.hi = p.hi.cwiseMax(q);
    }
    prims_.push_back(p);
    const int i = int(prims_.size()) - 1;
    if (governs) {
      governing_.push_back(i);
      entity_prims_[p.entity].push_back(i);
    }
  };
  for (int k = 0; k < int(lin.polygons.size()); ++k) {
    const model::LinearPolygon& lp = lin.polygons[k];
    size_t sides = 0;
    for (const auto& loop : lp.loops) sides += loop.size();
    // Polygons of many sides (planar faces with round holes) are queried by triangles:
    // each query is then constant time and the octree keeps only the nearby ones.
    std::vector<std::vector<std::vector<int>>> pieces;
    if (sides > 16 && !lp.triangles.empty())
      for (const auto& t : lp.triangles) pieces.push_back({{t[0], t[1], t[2]}});
    else
      pieces.push_back(lp.loops);
    for (const auto& loops : pieces) {
      Poly q;
      q.normal = lp.normal;
      q.origin = lin.points[loops[0][0]];
      const Vec3 axis = std::abs(q.normal.x()) < 0.6 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
      q.u = q.normal.cross(axis).normalized();
      q.v = q.normal.cross(q.u);
      std::vector<Vec3> pts;
      for (const auto& loop : loops) {
        for (int i : loop) {
          const Vec3 d = lin.points[i] - q.origin;
          q.pts.emplace_back(d.dot(q.u), d.dot(q.v));
          pts.push_back(lin.points[i]);
        }
        q.loop_end.push_back(int(q.pts.size()));
      }
      polys_.push_back(std::move(q));
      add({Prim::polygon, int(polys_.size()) - 1, model.index(lp.origin)}, true, pts);
    }
  }
  std::vector<std::vector<Vec3>> away(lin.points.size());
  for (int k = 0; k < int(lin.segments.size()); ++k) {
    const model::LinearSegment& s = lin.segments[k];
    const Vec3 a = lin.points[s.a], b = lin.points[s.b];
    Seg g{a, (b - a).normalized(), (b - a).norm()};
    segs_.push_back(g);
    away[s.a].push_back(g.dir);
    away[s.b].push_back(-g.dir);
    add({Prim::segment, k, owning_entity(model, s.origin)}, s.concave && g.length > 0, {a, b});
  }
  for (int k = 0; k < int(lin.corners.size()); ++k) {
    const model::LinearPoint& c = lin.corners[k];
    corners_.push_back({lin.points[c.point], away[c.point]});
    add({Prim::corner, k, owning_entity(model, c.origin)}, c.concave, {lin.points[c.point]});
  }
  for (int i = 0; i < int(prims_.size()); ++i)
    if (prims_[i].type == Prim::polygon) order_.push_back(i);
  if (!order_.empty()) build(0, int(order_.size()), 0);
}

int DistanceField::build(int first, int count, int depth) {
  Node n;
  n.lo = prims_[order_[first]].lo;
  n.hi = prims_[order_[first]].hi;
  for (int i = first; i < first + count; ++i) {
    n.lo = n.lo.cwiseMin(prims_[order_[i]].lo);
    n.hi = n.hi.cwiseMax(prims_[order_[i]].hi);
  }
  const int id = int(nodes_.size());
  nodes_.push_back(n);
  if (count <= 4 || depth > 40) {
    nodes_[id].first = first;
    nodes_[id].count = count;
    return id;
  }
  int axis = 0;
  (n.hi - n.lo).maxCoeff(&axis);
  auto mid = order_.begin() + first + count / 2;
  std::nth_element(order_.begin() + first, mid, order_.begin() + first + count, [&](int a, int b) {
    return prims_[a].lo[axis] + prims_[a].hi[axis] < prims_[b].lo[axis] + prims_[b].hi[axis];
  });
  const int l = build(first, count / 2, depth + 1);
  const int r = build(first + count / 2, count - count / 2, depth + 1);
  nodes_[id].left = l;
  nodes_[id].right = r;
  return id;
}

double DistanceField::poly_query(const Poly& q, const Vec3& p, double* h, bool* inside,
                                 Eigen::Vector2d* nearest2) const {
  const Vec3 d = p - q.origin;
  *h = d.dot(q.normal);
  const Eigen::Vector2d x(d.dot(q.u), d.dot(q.v));
  bool in = false;
  double best = kInf;
  int start = 0;
  for (int end : q.loop_end) {
    for (int i = start, j = end - 1; i < end; j = i++) {
      const Eigen::Vector2d& a = q.pts[j];
      const Eigen::Vector2d& b = q.pts[i];
      if ((a.y() > x.y()) != (b.y() > x.y()) &&
          x.x() < a.x() + (x.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
        in = !in;
      const Eigen::Vector2d ab = b - a;
      const double len2 = ab.squaredNorm();
      const double t = len2 > 0 ? std::clamp((x - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
      const Eigen::Vector2d c = a + t * ab;
      const double d2 = (x - c).squaredNorm();
      if (d2 < best) {
        best = d2;
        if (nearest2) *nearest2 = c;
      }
    }
    start = end;
  }
  *inside = in;
  if (in && nearest2) *nearest2 = x;
  return in ? 0.0 : best;
}

double DistanceField::distance(int i, const Vec3& p, Vec3* nearest) const {
  ++evaluations_;
  const Prim& pr = prims_[i];
  switch (pr.type) {
    case Prim::polygon: {
      const Poly& q = polys_[pr.source];
      double h;
      bool in;
      Eigen::Vector2d n2;
      const double d2 = poly_query(q, p, &h, &in, nearest ? &n2 : nullptr);
      if (nearest) *nearest = q.origin + n2.x() * q.u + n2.y() * q.v;
      return std::sqrt(h * h + d2);
    }
    case Prim::segment: {
      const Seg& s = segs_[pr.source];
      const double t = std::clamp((p - s.a).dot(s.dir), 0.0, s.length);
      const Vec3 c = s.a + t * s.dir;
      if (nearest) *nearest = c;
      return (p - c).norm();
    }
    case Prim::corner: {
      if (nearest) *nearest = corners_[pr.source].p;
      return (p - corners_[pr.source].p).norm();
    }
  }
  return kInf;
}

double DistanceField::restricted(int i, const Vec3& p) const {
  ++evaluations_;
  const Prim& pr = prims_[i];
  switch (pr.type) {
    case Prim::polygon: {
      double h;
      bool in;
      poly_query(polys_[pr.source], p, &h, &in, nullptr);
      return in && h <= tie_ ? std::abs(h) : kInf;
    }
    case Prim::segment: {
      const Seg& s = segs_[pr.source];
      const double t = (p - s.a).dot(s.dir);
      if (t < -tie_ || t > s.length + tie_) return kInf;
      return (p - (s.a + t * s.dir)).norm();
    }
    case Prim::corner: {
      const Corner& c = corners_[pr.source];
      for (const Vec3& a : c.away)
        if ((p - c.p).dot(a) > tie_) return kInf;
      return (p - c.p).norm();
    }
  }
  return kInf;
}

double DistanceField::zone_distance(int i, const Vec3& p) const {
  const Prim& pr = prims_[i];
  switch (pr.type) {
    case Prim::polygon: {
      double h;
      bool in;
      return std::sqrt(poly_query(polys_[pr.source], p, &h, &in, nullptr));
    }
    case Prim::segment: {
      const Seg& s = segs_[pr.source];
      const double t = (p - s.a).dot(s.dir);
      return std::max({0.0, -t, t - s.length});
    }
    case Prim::corner: {
      const Corner& c = corners_[pr.source];
      double z = 0;
      for (const Vec3& a : c.away) z = std::max(z, (p - c.p).dot(a));
      return z;
    }
  }
  return 0;
}

void DistanceField::bounds(int i, const Vec3& p, double limit, double* dist, double* zone) const {
  const Prim& pr = prims_[i];
  if (pr.type != Prim::polygon) {
    *dist = distance(i, p);
    *zone = zone_distance(i, p);
    return;
  }
  const Poly& q = polys_[pr.source];
  const double h = (p - q.origin).dot(q.normal);
  if (std::abs(h) > limit) {  // the plane alone is too far
    *dist = std::abs(h);
    *zone = 0;
    return;
  }
  ++evaluations_;
  double hh;
  bool in;
  const double d2 = poly_query(q, p, &hh, &in, nullptr);
  *dist = std::sqrt(h * h + d2);
  *zone = std::sqrt(d2);
}

double DistanceField::boundary_distance(const Vec3& p, double bound) const {
  if (nodes_.empty()) return kInf;
  if (bound < kInf) {
    // Searching below a slightly widened bound finds the same nearest polygon; if nothing
    // is found (the bound was wrong), search again without it.
    const double d = boundary_distance_below(p, bound * (1 + 1e-9) + tie_);
    if (d < kInf) return d;
  }
  return boundary_distance_below(p, kInf);
}

double DistanceField::boundary_distance_below(const Vec3& p, double limit) const {
  double best = kInf;
  double prune = limit;  // nodes at least this far are skipped
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (box_distance2(n.lo, n.hi, p) >= prune * prune) continue;
    if (n.left < 0) {
      for (int k = n.first; k < n.first + n.count; ++k) {
        const Prim& pr = prims_[order_[k]];
        if (box_distance2(pr.lo, pr.hi, p) >= prune * prune) continue;
        best = std::min(best, distance(order_[k], p));
        prune = std::min(prune, best);
      }
      continue;
    }
    const double dl = box_distance2(nodes_[n.left].lo, nodes_[n.left].hi, p);
    const double dr = box_distance2(nodes_[n.right].lo, nodes_[n.right].hi, p);
    if (top + 2 > 128) continue;
    if (dl < dr) {
      stack[top++] = n.right;
      stack[top++] = n.left;
    } else {
      stack[top++] = n.left;
      stack[top++] = n.right;
    }
  }
  return best;
}

double DistanceField::entity_distance(int entity, const Vec3& p, Vec3* nearest) const {
  double best = kInf;
  for (int i : entity_prims_[entity]) {
    if (box_distance2(prims_[i].lo, prims_[i].hi, p) >= best * best) continue;
    Vec3 c;
    const double d = distance(i, p, &c);
    if (d < best) {
      best = d;
      if (nearest) *nearest = c;
    }
  }
  return best;
}

int DistanceField::owner(const Vec3& p, const int* candidates, int n, double* distance_out,
                         double* margin) const {
  double closed = kInf, best = kInf, second = kInf;
  int who = -1;
  for (int k = 0; k < n; ++k) {
    const int i = candidates[k];
    const Prim& pr = prims_[i];
    double r;
    if (pr.type == Prim::polygon) {  // closed and restricted distance from one query
      ++evaluations_;
      double h;
      bool in;
      const double d2 = poly_query(polys_[pr.source], p, &h, &in, nullptr);
      closed = std::min(closed, std::sqrt(h * h + d2));
      r = in && h <= tie_ ? std::abs(h) : kInf;
    } else {
      closed = std::min(closed, distance(i, p));
      r = restricted(i, p);
    }
    if (r == kInf) continue;
    const int e = pr.entity;
    if (r < best) {
      if (e != who) second = best;
      best = r;
      who = e;
    } else if (e != who && r < second) {
      second = r;
    }
  }
  if (who < 0 || best > closed + tie_ + 1e-9 * best) return -1;
  if (distance_out) *distance_out = best;
  if (margin) *margin = second - best;
  return who;
}

int DistanceField::owner_sorted(const Vec3& p, const int* sorted, const int* pos,
                                const double* dist0, int n, double reach) const {
  double closed = kInf, best = kInf;
  int who = -1, best_pos = -1;
  for (int k = 0; k < n; ++k) {
    // Triangle inequality: no nearer than dist0 - reach, and the rest are no nearer.
    // Skipped primitives can neither own p nor be nearer than the owner, so neither the
    // owner nor the outside test changes.
    if (dist0[k] - reach - tie_ > best) break;
    const int i = sorted[k];
    const Prim& pr = prims_[i];
    double r;
    if (pr.type == Prim::polygon) {
      const Poly& q = polys_[pr.source];
      if (std::abs((p - q.origin).dot(q.normal)) > best) continue;  // the plane alone
      ++evaluations_;
      double h;
      bool in;
      const double d2 = poly_query(q, p, &h, &in, nullptr);
      closed = std::min(closed, std::sqrt(h * h + d2));
      r = in && h <= tie_ ? std::abs(h) : kInf;
    } else {
      closed = std::min(closed, distance(i, p));
      r = restricted(i, p);
    }
    // owner() keeps the first of equal restricted distances in list order.
    if (r < best || (r == best && r < kInf && pos[k] < best_pos)) {
      best = r;
      best_pos = pos[k];
      who = pr.entity;
    }
  }
  if (who < 0 || best > closed + tie_ + 1e-9 * best) return -1;
  return who;
}

int DistanceField::owner(const Vec3& p, double* distance_out, double* margin) const {
  return owner(p, governing_.data(), int(governing_.size()), distance_out, margin);
}

}  // namespace vorohex::voronoi::detail
