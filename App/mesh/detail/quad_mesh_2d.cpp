#include "mesh/detail/quad_mesh_2d.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <iterator>
#include <map>
#include <set>
#include <tuple>
#include <utility>

#include "mesh/detail/cusp_ladder.h"

namespace vorohex::mesh::detail {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Fbi = CGAL::Triangulation_face_base_with_info_2<int, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbi>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;
using Point = K::Point_2;

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

double corner(const Vec2& p, const Vec2& next, const Vec2& prev) {
  const Vec2 a = next - p, b = prev - p;
  const double la = a.norm(), lb = b.norm();
  if (la <= 0 || lb <= 0) return 0;
  return cross(a, b) / (la * lb);
}

// Face info = nesting level: 0 outside, 1 in the domain, 2 in a hole, ... (a constrained
// edge is crossed once per level); odd levels are the domain.
void mark_domains(Cdt& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
  std::deque<std::pair<Cdt::Face_handle, int>> seeds{{cdt.infinite_face(), 0}};
  while (!seeds.empty()) {
    auto [start, level] = seeds.front();
    seeds.pop_front();
    if (start->info() != -1) continue;
    std::deque<Cdt::Face_handle> queue{start};
    start->info() = level;
    while (!queue.empty()) {
      Cdt::Face_handle f = queue.front();
      queue.pop_front();
      for (int i = 0; i < 3; ++i) {
        Cdt::Face_handle n = f->neighbor(i);
        if (n->info() != -1) continue;
        if (cdt.is_constrained({f, i})) {
          seeds.emplace_back(n, level + 1);
        } else {
          n->info() = level;
          queue.push_back(n);
        }
      }
    }
  }
}

double segment_distance(const Vec2& a, const Vec2& b, const Vec2& p) {
  const Vec2 ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

// Buckets of boundary segments for "is p within r of the boundary" (r <= cell size).
class SegmentGrid {
 public:
  SegmentGrid(const std::vector<std::pair<Vec2, Vec2>>& segs, double cell) : segs_(segs), h_(cell) {
    lo_ = Vec2(1e300, 1e300);
    Vec2 hi(-1e300, -1e300);
    for (const auto& [a, b] : segs)
      lo_ = lo_.cwiseMin(a).cwiseMin(b), hi = hi.cwiseMax(a).cwiseMax(b);
    nx_ = std::max(1, int((hi.x() - lo_.x()) / h_) + 1);
    ny_ = std::max(1, int((hi.y() - lo_.y()) / h_) + 1);
    cells_.resize(std::size_t(nx_) * ny_);
    for (std::size_t s = 0; s < segs.size(); ++s) {
      const auto [a, b] = segs[s];
      const auto [i0, j0] = cell_of(a.cwiseMin(b));
      const auto [i1, j1] = cell_of(a.cwiseMax(b));
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) cells_[std::size_t(j) * nx_ + i].push_back(int(s));
    }
  }
  bool near(const Vec2& p, double r) const {
    const auto [ci, cj] = cell_of(p);
    for (int j = std::max(0, cj - 1); j <= std::min(ny_ - 1, cj + 1); ++j)
      for (int i = std::max(0, ci - 1); i <= std::min(nx_ - 1, ci + 1); ++i)
        for (int s : cells_[std::size_t(j) * nx_ + i])
          if (segment_distance(segs_[s].first, segs_[s].second, p) < r) return true;
    return false;
  }

 private:
  std::pair<int, int> cell_of(const Vec2& p) const {
    const int i = std::clamp(int(std::floor((p.x() - lo_.x()) / h_)), 0, nx_ - 1);
    const int j = std::clamp(int(std::floor((p.y() - lo_.y()) / h_)), 0, ny_ - 1);
    return {i, j};
  }
  const std::vector<std::pair<Vec2, Vec2>>& segs_;
  double h_;
  Vec2 lo_;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<int>> cells_;
};

// Quality-guarded smoothing of the nodes from `first_free` on.
class Smoother {
 public:
  Smoother(std::vector<Vec2>& p, const std::vector<std::array<int, 4>>& quads, int first_free)
      : p_(p), quads_(quads), first_(first_free) {
    const int n = int(p.size());
    std::vector<std::vector<int>> vq(n), vn(n);
    for (int q = 0; q < int(quads.size()); ++q)
      for (int c = 0; c < 4; ++c) {
        const int v = quads[q][c];
        vq[v].push_back(q);
        vn[v].push_back(quads[q][(c + 1) % 4]);
        vn[v].push_back(quads[q][(c + 3) % 4]);
      }
    for (auto& l : vn)
      std::sort(l.begin(), l.end()), l.erase(std::unique(l.begin(), l.end()), l.end());
    incident_ = std::move(vq);
    nbrs_ = std::move(vn);
  }

  void run(int passes) {
    const int n = int(p_.size());
    for (int pass = 0; pass < passes; ++pass) {
      for (int v = first_; v < n; ++v) laplace(v);
    }
    for (int pass = 0; pass < passes; ++pass) {
      bool any = false;
      for (int v = first_; v < n; ++v) any |= optimise(v);
      if (!any) break;
    }
  }

 private:
  struct Score {
    double min = 1, mean = 0;
  };
  Score score(int v) const {
    Score s;
    for (int q : incident_[v]) {
      const auto& e = quads_[q];
      const double x = quad_quality(p_[e[0]], p_[e[1]], p_[e[2]], p_[e[3]]);
      s.min = std::min(s.min, x);
      s.mean += x;
    }
    if (!incident_[v].empty()) s.mean /= incident_[v].size();
    return s;
  }
  // Length-weighted umbrella: long edges pull harder, which evens out edge lengths.
  void laplace(int v) {
    if (nbrs_[v].empty()) return;
    Vec2 sum = Vec2::Zero();
    double w = 0;
    for (int u : nbrs_[v]) {
      const double l = (p_[u] - p_[v]).norm();
      sum += l * p_[u];
      w += l;
    }
    if (w <= 0) return;
    const Score old = score(v);
    const Vec2 keep = p_[v];
    p_[v] = sum / w;
    const Score now = score(v);
    const bool better = now.min >= old.min - 1e-12 || (now.min >= 0.5 && now.mean > old.mean);
    if (!better) p_[v] = keep;
  }
  // Pattern search on the worst incident quad's quality (min, then mean).
  bool optimise(int v) {
    Score best = score(v);
    if (best.min >= 0.8 || nbrs_[v].empty()) return false;
    double step = 0;
    for (int u : nbrs_[v]) step += (p_[u] - p_[v]).norm();
    step *= 0.1 / nbrs_[v].size();
    bool moved = false;
    for (int level = 0; level < 5; ++level, step *= 0.5) {
      for (int d = 0; d < 8; ++d) {
        const double a = d * M_PI / 4;
        const Vec2 keep = p_[v];
        p_[v] = keep + step * Vec2(std::cos(a), std::sin(a));
        const Score now = score(v);
        if (now.min > best.min + 1e-9 ||
            (now.min >= best.min - 1e-12 && now.mean > best.mean + 1e-9)) {
          best = now;
          moved = true;
          --level;  // keep the step while it helps
          break;
        }
        p_[v] = keep;
      }
    }
    return moved;
  }

  std::vector<Vec2>& p_;
  const std::vector<std::array<int, 4>>& quads_;
  int first_;
  std::vector<std::vector<int>> incident_, nbrs_;
};

}  // namespace

double quad_quality(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  return std::min({corner(a, b, d), corner(b, c, a), corner(c, d, b), corner(d, a, c)});
}

namespace {

// Lattice points for a graded size: a quadtree over the lattice frame (root cells of side
// H), each cell split while it is more than 1.5 times twice the local size at its centre, then
// balanced so that edge neighbours differ by at most one level. Returns the leaf corners with
// the side of the smallest leaf at each (in the frame's coordinates (i, j) x cell side).
struct LatticePoint {
  Vec2 p;
  double spacing;
};
std::vector<LatticePoint> graded_lattice(const Vec2& anchor, const Vec2& u, const Vec2& v, double H,
                                         long i0, long i1, long j0, long j1,
                                         const SizeAt& size_at) {
  constexpr int kMaxLevel = 8;
  using Key = std::tuple<int, long, long>;  // level, i, j (in cells of side H / 2^level)
  std::set<Key> leaves;
  std::vector<Key> stack;
  for (long j = j0; j < j1; ++j)
    for (long i = i0; i < i1; ++i) stack.emplace_back(0, i, j);
  auto centre = [&](const Key& k) {
    const auto [l, i, j] = k;
    const double side = H / double(1L << l);
    return Vec2(anchor + (double(i) + 0.5) * side * u + (double(j) + 0.5) * side * v);
  };
  auto split = [&](const Key& k, std::vector<Key>& out) {
    const auto [l, i, j] = k;
    for (long dj = 0; dj < 2; ++dj)
      for (long di = 0; di < 2; ++di) out.emplace_back(l + 1, 2 * i + di, 2 * j + dj);
  };
  while (!stack.empty()) {
    const Key k = stack.back();
    stack.pop_back();
    const double side = H / double(1L << std::get<0>(k));
    if (std::get<0>(k) < kMaxLevel && side > 1.5 * 2 * size_at(centre(k))) {
      split(k, stack);
    } else {
      leaves.insert(k);
    }
  }
  // The leaf holding cell (l, i, j)'s area, if one at level <= l holds it.
  auto holder = [&](int l, long i, long j) -> const Key* {
    for (int m = l; m >= 0; --m) {
      const long s = l - m;
      auto it = leaves.find(Key(m, i >> s, j >> s));
      if (it != leaves.end()) return &*it;
    }
    return nullptr;
  };
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<Key> too_big;
    for (const Key& k : leaves) {
      const auto [l, i, j] = k;
      if (l < 2) continue;
      const long nb[4][2] = {{i + 1, j}, {i - 1, j}, {i, j + 1}, {i, j - 1}};
      for (const auto& n : nb) {
        const Key* h = holder(l, n[0], n[1]);
        if (h != nullptr && std::get<0>(*h) < l - 1) too_big.push_back(*h);
      }
    }
    std::sort(too_big.begin(), too_big.end());
    too_big.erase(std::unique(too_big.begin(), too_big.end()), too_big.end());
    for (const Key& k : too_big) {
      leaves.erase(k);
      std::vector<Key> kids;
      split(k, kids);
      leaves.insert(kids.begin(), kids.end());
      changed = true;
    }
  }
  std::map<std::pair<long, long>, double> corners;  // at the finest level's coordinates
  for (const auto& [l, i, j] : leaves) {
    const long s = 1L << (kMaxLevel - l);
    const double side = H / double(1L << l);
    for (long dj = 0; dj < 2; ++dj)
      for (long di = 0; di < 2; ++di) {
        auto [it, fresh] = corners.emplace(std::make_pair((i + di) * s, (j + dj) * s), side);
        if (!fresh) it->second = std::min(it->second, side);
      }
  }
  std::vector<LatticePoint> out;
  out.reserve(corners.size());
  const double fine = H / double(1L << kMaxLevel);
  for (const auto& [ij, side] : corners)
    out.push_back({anchor + double(ij.first) * fine * u + double(ij.second) * fine * v, side});
  return out;
}

double worst_quad(const QuadMesh2d& m) {
  double lo = 1;
  for (const auto& q : m.quads)
    lo = std::min(lo, quad_quality(m.points[q[0]], m.points[q[1]], m.points[q[2]], m.points[q[3]]));
  return lo;
}

// How the coarse boundary (every other node of each loop) is chosen.
enum class Coarse {
  sharpest,   // the parity holding the most turn: corners stay corners
  least_turn  // the parity whose midpoints turn least (largest turn, then sum)
};

// `shift`: the lattice's offset from the first boundary node, in lattice cells.
QuadMesh2d lattice_mesh_by(const std::vector<std::vector<Vec2>>& loops, double size,
                           int smoothing_passes, const SizeAt& size_at, Coarse coarse,
                           const Vec2& shift = Vec2::Zero()) {
  QuadMesh2d out;
  if (loops.empty() || !(size > 0)) {
    out.error = "no boundary loops or no positive size";
    return out;
  }
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const std::size_t n = loops[l].size();
    if (n % 2 != 0) {
      out.error = "boundary loop " + std::to_string(l) + " has an odd number of nodes (" +
                  std::to_string(n) + ")";
      return out;
    }
    if (n < 6 && !(n == 4 && loops.size() == 1)) {
      out.error = "boundary loop " + std::to_string(l) + " has only " + std::to_string(n) +
                  " nodes (at least 6 are needed, or 4 for a face without holes)";
      return out;
    }
  }
  for (const auto& loop : loops) out.points.insert(out.points.end(), loop.begin(), loop.end());
  const int nb = int(out.points.size());
  if (loops.size() == 1 && nb == 4) {
    const std::vector<Vec2>& b = out.points;
    if (quad_quality(b[0], b[1], b[2], b[3]) > 0) {
      out.quads.push_back({0, 1, 2, 3});
      return out;
    }
    // Four nodes with a straight (or reflex) angle at one: a triangle with one edge of two
    // intervals, as a small sub-volume's end gets. A pillow: an inner quad, its corners
    // halfway from the centre to the boundary nodes, and a quad between each boundary edge
    // and the inner quad's edge facing it. The inner corner facing the straight angle goes
    // farther out (else the inner quad has the straight angle too).
    const Vec2 centre = 0.25 * (b[0] + b[1] + b[2] + b[3]);
    int flat = 0;  // the node with the largest interior angle (counter-clockwise loop)
    double widest = -1e300;
    for (int k = 0; k < 4; ++k) {
      const Vec2 in = b[k] - b[(k + 3) % 4], out_ = b[(k + 1) % 4] - b[k];
      const double turn = std::atan2(in.x() * out_.y() - in.y() * out_.x(), in.dot(out_));
      if (-turn > widest) widest = -turn, flat = k;  // interior angle = pi - turn
    }
    for (const double t : {0.75, 0.85, 0.65, 0.95}) {
      out.points.resize(4);
      out.quads.clear();
      for (int k = 0; k < 4; ++k)
        out.points.push_back(centre + (k == flat ? t : 0.5) * (out.points[k] - centre));
      for (int k = 0; k < 4; ++k) out.quads.push_back({k, (k + 1) % 4, 4 + (k + 1) % 4, 4 + k});
      out.quads.push_back({4, 5, 6, 7});
      bool valid = true;
      for (const auto& q : out.quads)
        valid = valid && quad_quality(out.points[q[0]], out.points[q[1]], out.points[q[2]],
                                      out.points[q[3]]) > 0;
      if (valid) return out;
    }
    out.points.resize(4);
    out.quads.clear();
    out.error = "the four boundary nodes do not make a valid quad, nor a pillowed one";
    return out;
  }

  // Coarse boundary (every other node) as constraints.
  Cdt cdt;
  std::vector<std::pair<Vec2, Vec2>> segs;
  std::map<std::pair<int, int>, int> midpoint;  // coarse boundary edge -> fine node
  double cx = 0, sx = 0;                        // dominant direction (angle x 4)
  int base = 0, inserted = 0;
  for (const auto& loop : loops) {
    const int n = int(loop.size());
    // A corner that became an edge midpoint would give a quad with a straight angle, and a
    // midpoint far off its coarse edge (a hole's arc of few, unequal segments) can fold the
    // quads of a thin triangle beside it.
    double turn[2] = {0, 0}, worst[2] = {0, 0};
    for (int i = 0; i < n; ++i) {
      const Vec2 a = loop[i] - loop[(i + n - 1) % n], b = loop[(i + 1) % n] - loop[i];
      const double t = std::abs(std::atan2(cross(a, b), a.dot(b)));
      turn[i % 2] += t;
      worst[i % 2] = std::max(worst[i % 2], t);
    }
    // worst[k]: the largest turn at a node of parity k, which is a midpoint when the coarse
    // nodes take the other parity.
    const int most_turn = turn[1] > turn[0] + 1e-9 ? 1 : 0;
    const int offset = coarse == Coarse::sharpest || std::abs(worst[0] - worst[1]) <= 1e-9
                           ? most_turn
                           : (worst[0] > worst[1] ? 0 : 1);
    std::vector<Cdt::Vertex_handle> vh;
    for (int i = offset; i < n; i += 2) {
      vh.push_back(cdt.insert(Point(loop[i].x(), loop[i].y())));
      vh.back()->info() = base + i;
      ++inserted;
    }
    for (int k = 0; k < n / 2; ++k) {
      const int i = offset + 2 * k, j = (i + 2) % n;
      cdt.insert_constraint(vh[k], vh[(k + 1) % (n / 2)]);
      midpoint[{std::min(base + i, base + j), std::max(base + i, base + j)}] = base + (i + 1) % n;
      segs.emplace_back(loop[i], loop[j]);
      const Vec2 d = loop[j] - loop[i];
      const double a = 4 * std::atan2(d.y(), d.x()), w = d.norm();
      cx += w * std::cos(a), sx += w * std::sin(a);
    }
    for (int i = 0; i < n; ++i) segs.emplace_back(loop[i], loop[(i + 1) % n]);
    base += n;
  }
  if (int(cdt.number_of_vertices()) != inserted) {
    out.error = "boundary nodes coincide or boundary loops intersect";
    return out;
  }
  mark_domains(cdt);

  // Square lattice at twice the size, anchored at the first node, kept off the boundary.
  const double H = 2 * size;
  const double theta = std::atan2(sx, cx) / 4;
  const Vec2 u(std::cos(theta), std::sin(theta)), v(-u.y(), u.x());
  const Vec2 anchor = loops[0][0] + shift.x() * H * u + shift.y() * H * v;
  double s0 = 1e300, s1 = -1e300, t0 = 1e300, t1 = -1e300;
  for (const Vec2& p : out.points) {
    s0 = std::min(s0, (p - anchor).dot(u)), s1 = std::max(s1, (p - anchor).dot(u));
    t0 = std::min(t0, (p - anchor).dot(v)), t1 = std::max(t1, (p - anchor).dot(v));
  }
  const SegmentGrid grid(segs, H);
  std::vector<Vec2> lattice;
  Cdt::Face_handle hint;
  auto keep = [&](const Vec2& p, double spacing) {
    hint = cdt.locate(Point(p.x(), p.y()), hint);
    if (cdt.is_infinite(hint) || hint->info() % 2 != 1) return;
    if (grid.near(p, 0.5 * spacing)) return;
    lattice.push_back(p);
  };
  const long i0 = long(std::floor(s0 / H)), i1 = long(std::ceil(s1 / H));
  const long j0 = long(std::floor(t0 / H)), j1 = long(std::ceil(t1 / H));
  if (size_at) {
    for (const LatticePoint& q : graded_lattice(anchor, u, v, H, i0, i1, j0, j1, size_at))
      keep(q.p, q.spacing);
  } else {
    for (long j = j0; j <= j1; ++j)
      for (long i = i0; i <= i1; ++i) keep(anchor + double(i) * H * u + double(j) * H * v, H);
  }
  Cdt::Vertex_handle vhint;
  for (std::size_t i = 0; i < lattice.size(); ++i) {
    const Point p(lattice[i].x(), lattice[i].y());
    vhint = vhint == Cdt::Vertex_handle() ? cdt.insert(p) : cdt.insert(p, vhint->face());
    vhint->info() = nb + int(i);
  }
  out.points.insert(out.points.end(), lattice.begin(), lattice.end());
  if (cdt.number_of_vertices() != std::size_t(inserted) + lattice.size()) {
    out.error = "the triangulation split the boundary";
    return out;
  }
  mark_domains(cdt);

  // Triangles of the domain, then greedy merging of good triangle pairs into quads.
  std::vector<Cdt::Face_handle> tris;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
    if (f->info() % 2 == 1) tris.push_back(f);
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
  for (std::size_t t = 0; t < tris.size(); ++t) tris[t]->info() = int(t);
  struct Pair {
    double quality;
    int t1, t2;
    std::array<int, 4> quad;
  };
  std::vector<Pair> pairs;
  const auto& P = out.points;
  for (std::size_t t = 0; t < tris.size(); ++t) {
    const auto f = tris[t];
    for (int i = 0; i < 3; ++i) {
      const auto n = f->neighbor(i);
      if (n->info() <= int(t) || cdt.is_constrained({f, i})) continue;
      const int p = f->vertex(i)->info(), q = f->vertex(Cdt::ccw(i))->info(),
                r = f->vertex(Cdt::cw(i))->info(), s = n->vertex(n->index(f))->info();
      const std::array<int, 4> quad{p, q, s, r};
      const double x = quad_quality(P[p], P[q], P[s], P[r]);
      if (x >= 0.5) pairs.push_back({x, int(t), n->info(), quad});
    }
  }
  std::sort(pairs.begin(), pairs.end(),
            [](const Pair& a, const Pair& b) { return a.quality > b.quality; });
  std::vector<char> used(tris.size(), 0);
  std::vector<std::vector<int>> cells;  // counter-clockwise polygons of 3 or 4 nodes
  for (const Pair& pr : pairs) {
    if (used[pr.t1] || used[pr.t2]) continue;
    used[pr.t1] = used[pr.t2] = 1;
    cells.push_back({pr.quad.begin(), pr.quad.end()});
  }
  for (std::size_t t = 0; t < tris.size(); ++t)
    if (!used[t])
      cells.push_back(
          {tris[t]->vertex(0)->info(), tris[t]->vertex(1)->info(), tris[t]->vertex(2)->info()});

  // Split: each cell of k nodes gives k quads around its centre.
  auto mid = [&](int a, int b) {
    const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
    auto it = midpoint.find(key);
    if (it != midpoint.end()) return it->second;
    out.points.push_back(0.5 * (out.points[a] + out.points[b]));
    return midpoint[key] = int(out.points.size()) - 1;
  };
  for (const auto& c : cells) {
    const int k = int(c.size());
    Vec2 g = Vec2::Zero();
    for (int a : c) g += out.points[a];
    out.points.push_back(g / k);
    const int centre = int(out.points.size()) - 1;
    for (int i = 0; i < k; ++i) {
      const int a = c[i], next = c[(i + 1) % k], prev = c[(i + k - 1) % k];
      out.quads.push_back({a, mid(a, next), centre, mid(prev, a)});
    }
  }

  Smoother(out.points, out.quads, nb).run(smoothing_passes);
  if (worst_quad(out) <= 0) out.error = "a quad is inverted after smoothing";
  return out;
}

// The lattice mesh with the coarse boundary at the parities of least turning midpoints;
// when that folds a quad or leaves one poor (a hole close to another boundary), also with
// the sharpest corners coarse, and the better of the two (neither choice is always right).
// When both fold a quad, the same with the lattice shifted by half a cell, then at 0.7, 0.5
// and 0.4 of the size inside (the boundary nodes are kept; finer inner nodes fit a gap
// narrower than the size), until one is at least 0.3, keeping the best: a bore 1.6 from a
// reflex corner at size 5, HexMe i22's cap region, folds at the size and its shift. A mesh
// that holds is kept as it is, even when poor: a better 2-D minimum from a finer lattice
// gave worse hexahedra after smoothing on HexMe n02 and n03 (0.197 and 0.207 -> 0.108 and
// 0.110) and i01 (0.403 -> 0.343).
QuadMesh2d lattice_mesh(const std::vector<std::vector<Vec2>>& loops, double size,
                        int smoothing_passes, const SizeAt& size_at) {
  constexpr double kGood = 0.5, kPoor = 0.3;
  QuadMesh2d best;
  double best_q = -3;
  const std::pair<double, Vec2> variants[] = {{1.0, Vec2::Zero()},
                                              {1.0, Vec2(0.5, 0.5)},
                                              {0.7, Vec2::Zero()},
                                              {0.5, Vec2::Zero()},
                                              {0.4, Vec2::Zero()}};
  for (std::size_t i = 0; i < std::size(variants); ++i) {
    if (i == 1 && best_q > 0) break;  // the lattice at the size holds: kept
    if (i > 1 && best_q >= kPoor) break;
    const auto& [factor, shift] = variants[i];
    const SizeAt scaled =
        size_at && factor != 1.0
            ? SizeAt([&size_at, f = factor](const Vec2& q) { return f * size_at(q); })
            : size_at;
    for (Coarse coarse : {Coarse::least_turn, Coarse::sharpest}) {
      QuadMesh2d m = lattice_mesh_by(loops, factor * size, smoothing_passes, scaled, coarse, shift);
      const double q = m.error.empty() ? worst_quad(m) : -2;
      // An error kept only while nothing better came (its message says why).
      if (q > best_q) best = std::move(m), best_q = q;
      if (best_q >= kGood) break;
    }
  }
  return best;
}

bool segments_cross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 &&
         d4 != 0;
}

double mean_segment(const std::vector<Vec2>& p, const std::vector<int>& loop) {
  double sum = 0;
  for (std::size_t i = 0; i < loop.size(); ++i)
    sum += (p[loop[(i + 1) % loop.size()]] - p[loop[i]]).norm();
  return sum / double(loop.size());
}

// The loop's nodes moved into the domain (on the left of the loop's direction) by t, along
// the bisector of the two segments' normals (mitred, at most 2 t).
std::vector<Vec2> offset_loop(const std::vector<Vec2>& p, const std::vector<int>& loop, double t) {
  const int n = int(loop.size());
  std::vector<Vec2> out(n);
  for (int i = 0; i < n; ++i) {
    const Vec2 a = p[loop[(i + n - 1) % n]], b = p[loop[i]], c = p[loop[(i + 1) % n]];
    const Vec2 e0 = (b - a).normalized(), e1 = (c - b).normalized();
    const Vec2 n0(-e0.y(), e0.x()), n1(-e1.y(), e1.x());
    Vec2 bis = n0 + n1;
    const double len = bis.norm();
    bis = len > 1e-12 ? Vec2(bis / len) : n0;
    out[i] = b + t * bis / std::max(0.5, bis.dot(n0));
  }
  return out;
}

// Whether a loop's turns are all gentle (a circle, an ellipse, a rounded slot): only such
// loops get rings (around a hole with corners, or along an outline with corners, the lattice
// aligned with the sides gives rectangles where rings would give mitred corners).
bool smooth_loop(const std::vector<Vec2>& l) {
  const int n = int(l.size());
  for (int i = 0; i < n; ++i) {
    const Vec2 a = l[i] - l[(i + n - 1) % n], b = l[(i + 1) % n] - l[i];
    if (std::abs(std::atan2(cross(a, b), a.dot(b))) > 0.6) return false;  // ~35 degrees
  }
  return true;
}

QuadMesh2d mesh_without_ladders(const std::vector<std::vector<Vec2>>& loops, double size,
                                int smoothing_passes, int ring_layers, const SizeAt& size_at) {
  if (ring_layers <= 0 || loops.empty() || !(size > 0))
    return lattice_mesh(loops, size, smoothing_passes, size_at);
  const std::size_t L = loops.size();
  std::vector<Vec2> pts;
  std::vector<std::vector<int>> front(L);
  for (std::size_t l = 0; l < L; ++l) {
    if (loops[l].size() < 6 || loops[l].size() % 2)
      return lattice_mesh(loops, size, smoothing_passes, size_at);
    for (const Vec2& q : loops[l]) {
      front[l].push_back(int(pts.size()));
      pts.push_back(q);
    }
  }
  std::vector<char> growing(L);
  for (std::size_t l = 0; l < L; ++l) growing[l] = smooth_loop(loops[l]);
  std::vector<std::array<int, 4>> ring_quads;
  int first_free = -1;  // the nodes after the first rings: smoothed with the rest
  for (int layer = 0; layer < ring_layers; ++layer) {
    if (layer == 1) first_free = int(pts.size());
    for (std::size_t l = 0; l < L; ++l) {
      if (!growing[l]) continue;
      const std::vector<int>& f = front[l];
      const int n = int(f.size());
      const double t = std::min(mean_segment(pts, f), size_at ? size_at(pts[f[0]]) : size);
      const std::vector<Vec2> ring = offset_loop(pts, f, t);
      bool ok = true;
      double seg = 0;
      for (int i = 0; i < n && ok; ++i) {
        const int j = (i + 1) % n;
        seg += (ring[j] - ring[i]).norm();
        ok = quad_quality(pts[f[i]], pts[f[j]], ring[j], ring[i]) >= 0.5;
      }
      // Growing (around a hole) up to 2 x size; shrinking (inside an outline) down to 0.7 x size.
      const double before = mean_segment(pts, f);
      ok = ok && seg / n <= 2 * size && (seg / n >= before || seg / n >= 0.7 * size);
      // Not crossing itself, and at least a ring's width clear of every other loop's front.
      for (int i = 0; i < n && ok; ++i)
        for (int k = i + 2; k < n && ok; ++k)
          if ((k + 1) % n != i)
            ok = !segments_cross(ring[i], ring[(i + 1) % n], ring[k], ring[(k + 1) % n]);
      for (std::size_t o = 0; o < L && ok; ++o) {
        if (o == l) continue;
        const std::vector<int>& g = front[o];
        for (std::size_t k = 0; k < g.size() && ok; ++k) {
          const Vec2& a = pts[g[k]];
          const Vec2& b = pts[g[(k + 1) % g.size()]];
          for (int i = 0; i < n && ok; ++i)
            ok = segment_distance(a, b, ring[i]) > t &&
                 !segments_cross(a, b, ring[i], ring[(i + 1) % n]) &&
                 segment_distance(ring[i], ring[(i + 1) % n], a) > t;
        }
      }
      if (!ok) {
        growing[l] = 0;
        continue;
      }
      std::vector<int> next(n);
      for (int i = 0; i < n; ++i) {
        next[i] = int(pts.size());
        pts.push_back(ring[i]);
      }
      for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n;
        ring_quads.push_back({f[i], f[j], next[j], next[i]});
      }
      front[l] = std::move(next);
    }
  }
  if (ring_quads.empty()) return lattice_mesh(loops, size, smoothing_passes, size_at);

  // The rest of the domain inside the last rings.
  std::vector<std::vector<Vec2>> inner(L);
  std::vector<int> index;  // the lattice mesh's boundary node k -> pts index
  for (std::size_t l = 0; l < L; ++l)
    for (int v : front[l]) {
      inner[l].push_back(pts[v]);
      index.push_back(v);
    }
  QuadMesh2d core = lattice_mesh(inner, size, smoothing_passes, size_at);
  if (!core.error.empty()) return lattice_mesh(loops, size, smoothing_passes, size_at);
  QuadMesh2d out;
  out.points = std::move(pts);
  if (first_free < 0) first_free = int(out.points.size());
  for (std::size_t k = index.size(); k < core.points.size(); ++k) {
    index.push_back(int(out.points.size()));
    out.points.push_back(core.points[k]);
  }
  out.quads = std::move(ring_quads);
  for (const auto& q : core.quads)
    out.quads.push_back({index[q[0]], index[q[1]], index[q[2]], index[q[3]]});
  // The first rings stay where they follow the loops; the outer rings relax into the rest.
  Smoother(out.points, out.quads, first_free).run(smoothing_passes);
  for (const auto& q : out.quads)
    if (quad_quality(out.points[q[0]], out.points[q[1]], out.points[q[2]], out.points[q[3]]) <= 0)
      return lattice_mesh(loops, size, smoothing_passes, size_at);
  return out;
}

}  // namespace

QuadMesh2d quad_mesh_2d(const std::vector<std::vector<Vec2>>& loops, double size,
                        int smoothing_passes, int ring_layers, const SizeAt& size_at) {
  const CuspLadders ladders = cusp_ladders(loops, size);
  if (ladders.quads.empty())
    return mesh_without_ladders(loops, size, smoothing_passes, ring_layers, size_at);
  const QuadMesh2d rest =
      mesh_without_ladders(ladders.loops, size, smoothing_passes, ring_layers, size_at);
  QuadMesh2d out;
  for (const auto& loop : loops) out.points.insert(out.points.end(), loop.begin(), loop.end());
  const int nb = int(out.points.size());
  std::vector<int> given;  // the rest's boundary nodes -> the given nodes
  for (const auto& l : ladders.index) given.insert(given.end(), l.begin(), l.end());
  const int rest_nb = int(given.size());
  for (std::size_t k = std::size_t(rest_nb); k < rest.points.size(); ++k)
    out.points.push_back(rest.points[k]);
  out.quads = ladders.quads;
  for (const auto& q : rest.quads) {
    std::array<int, 4> r{};
    for (int c = 0; c < 4; ++c)
      r[c] = q[c] < rest_nb ? given[std::size_t(q[c])] : nb + q[c] - rest_nb;
    out.quads.push_back(r);
  }
  out.error = rest.error;
  return out;
}

}  // namespace vorohex::mesh::detail
