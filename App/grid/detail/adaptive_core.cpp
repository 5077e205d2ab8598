#include "grid/detail/adaptive_core.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "core/hex_mesh.h"
#include "grid/detail/core_cells.h"
#include "grid/detail/pillow.h"
#include "occ/classify_points.h"
#include "quality/scaled_jacobian.h"

namespace vorohex::grid::detail {
namespace {

using core::Vec3;
using Hex = std::array<std::int32_t, 8>;

// The tessellation's triangles bucketed by the base grid's cells (frame coordinates), for
// distances capped at a few cells.
class Triangles {
 public:
  Triangles(const GridFrame& frame, const occ::Tessellation& t) : frame_(frame) {
    for (int a = 0; a < 3; ++a) n_[a] = std::max(frame.cells(a), 1);
    buckets_.resize(std::size_t(n_[0]) * n_[1] * n_[2]);
    for (const occ::FaceTriangulation& f : t.faces) {
      const std::size_t first = points_.size();
      for (const Vec3& p : f.nodes) points_.push_back(frame.to_frame(p));
      for (const auto& tri : f.triangles) {
        const std::array<std::size_t, 3> v = {first + tri[0], first + tri[1], first + tri[2]};
        const Vec3 lo = points_[v[0]].cwiseMin(points_[v[1]]).cwiseMin(points_[v[2]]);
        const Vec3 hi = points_[v[0]].cwiseMax(points_[v[1]]).cwiseMax(points_[v[2]]);
        const std::uint32_t id = std::uint32_t(tris_.size());
        tris_.push_back(v);
        visit(lo, hi, [&](std::size_t b) { buckets_[b].push_back(id); });
      }
    }
  }
  // Distance from q (frame coordinates) to the boundary, or cap when it is farther.
  double distance(const Vec3& q, double cap) const {
    double best = cap;
    const Vec3 lo = q.array() - cap, hi = q.array() + cap;
    visit(lo, hi, [&](std::size_t b) {
      for (std::uint32_t id : buckets_[b]) {
        const auto& v = tris_[id];
        best =
            std::min(best, point_triangle_distance(q, points_[v[0]], points_[v[1]], points_[v[2]]));
      }
    });
    return best;
  }

 private:
  template <class F>
  void visit(const Vec3& lo, const Vec3& hi, F&& f) const {
    std::array<int, 3> a0, a1;
    for (int a = 0; a < 3; ++a) {
      const std::vector<double>& l = frame_.lines[a];
      // Cells touching [lo, hi], those that only share a plane with it included.
      a0[a] = std::clamp(int(std::lower_bound(l.begin(), l.end(), lo[a]) - l.begin()) - 1, 0,
                         n_[a] - 1);
      a1[a] = std::clamp(int(std::upper_bound(l.begin(), l.end(), hi[a]) - l.begin()) - 1, 0,
                         n_[a] - 1);
    }
    for (int k = a0[2]; k <= a1[2]; ++k)
      for (int j = a0[1]; j <= a1[1]; ++j)
        for (int i = a0[0]; i <= a1[0]; ++i)
          f(std::size_t(i) + std::size_t(n_[0]) * (std::size_t(j) + std::size_t(n_[1]) * k));
  }
  const GridFrame& frame_;
  std::array<int, 3> n_;
  std::vector<Vec3> points_;
  std::vector<std::array<std::size_t, 3>> tris_;
  std::vector<std::vector<std::uint32_t>> buckets_;
};

// Inside the solid, for points far from the boundary: points joined by segments that
// cannot cross it (the sum of their distances exceeds the length, chord error allowed)
// share one answer (vote_inside).
std::vector<char> inside(const occ::Solid& solid, const std::vector<Vec3>& points,
                         const std::vector<double>& dist,
                         const std::vector<std::pair<std::size_t, std::size_t>>& segments,
                         double far, double deflection, std::size_t& calls) {
  const std::size_t n = points.size();
  UnionFind uf(n);
  for (const auto& [a, b] : segments)
    if (dist[a] > far && dist[b] > far &&
        dist[a] + dist[b] > (points[a] - points[b]).norm() + 2 * deflection)
      uf.unite(a, b);
  return vote_inside(
      solid, uf, dist, far, [&](std::size_t i) { return points[i]; },
      std::max(solid.tolerance(), 1e-9 * solid.diagonal()), calls);
}

// Nodes where the boundary of the hexahedra `keep` marks is not a manifold: an edge of
// other than two boundary quads, or a node whose boundary quads are not one fan.
std::vector<std::int32_t> pinched_nodes(const std::vector<Hex>& hexes,
                                        const std::vector<char>& keep) {
  std::unordered_map<QuadKey, int, QuadKeyHash> uses;
  for (std::size_t h = 0; h < hexes.size(); ++h)
    if (keep[h])
      for (int f = 0; f < 6; ++f) ++uses[quad_key(hexes[h], f)];
  std::vector<std::array<std::int32_t, 4>> quads;
  for (std::size_t h = 0; h < hexes.size(); ++h)
    if (keep[h])
      for (int f = 0; f < 6; ++f)
        if (uses[quad_key(hexes[h], f)] == 1) {
          const auto& c = core::kHexFaces[f];
          quads.push_back({hexes[h][c[0]], hexes[h][c[1]], hexes[h][c[2]], hexes[h][c[3]]});
        }
  auto edge = [](std::int32_t a, std::int32_t b) {
    return (std::int64_t(std::min(a, b)) << 32) | std::int64_t(std::max(a, b));
  };
  std::unordered_map<std::int64_t, int> edge_uses;
  std::unordered_map<std::int32_t, std::vector<std::size_t>> quads_at;
  for (std::size_t q = 0; q < quads.size(); ++q)
    for (int c = 0; c < 4; ++c) {
      ++edge_uses[edge(quads[q][c], quads[q][(c + 1) % 4])];
      quads_at[quads[q][c]].push_back(q);
    }
  std::unordered_set<std::int32_t> bad;
  for (const auto& [e, n] : edge_uses)
    if (n != 2) bad.insert(std::int32_t(e >> 32)), bad.insert(std::int32_t(e & 0xffffffff));
  for (const auto& [v, qs] : quads_at) {
    // One fan: the quads at v connected through the edges at v they share.
    std::vector<int> seen(qs.size(), 0);
    std::vector<std::size_t> stack{0};
    seen[0] = 1;
    std::size_t reached = 1;
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      for (std::size_t j = 0; j < qs.size(); ++j) {
        if (seen[j]) continue;
        const auto &a = quads[qs[i]], &b = quads[qs[j]];
        bool share = false;
        for (int c = 0; c < 4 && !share; ++c) {
          if (a[c] != v) continue;
          for (std::int32_t w : {a[(c + 1) % 4], a[(c + 3) % 4]})
            share = share || std::find(b.begin(), b.end(), w) != b.end();
        }
        if (share) seen[j] = 1, ++reached, stack.push_back(j);
      }
    }
    if (reached != qs.size()) bad.insert(v);
  }
  return {bad.begin(), bad.end()};
}

}  // namespace

AdaptiveCore adaptive_core(const GridFrame& frame, const occ::Solid& solid,
                           const occ::Tessellation& tess, const AdaptiveCoreOptions& o,
                           const core::Progress& progress) {
  AdaptiveCore out;
  const Triangles triangles(frame, tess);
  // Distances by lattice point, with the cap they were computed at (a capped value is
  // computed again when a larger cap is asked).
  std::unordered_map<LatticePoint, std::pair<double, double>, LatticeHash> dist_memo;
  std::int64_t unit = 6;
  for (int l = 0; l < o.max_level; ++l) unit *= 3;
  auto size_at = [&](int level) { return o.size / std::pow(3.0, level); };
  auto distance = [&](const LatticePoint& p, const Vec3& world, double cap) {
    auto& [d, cap_used] = dist_memo.try_emplace(p, 0.0, -1.0).first->second;
    if (cap_used < cap && d >= cap_used) {
      d = triangles.distance(frame.to_frame(world), cap);
      cap_used = cap;
    }
    return std::min(d, cap);
  };
  // The core cells of each level so far, by origin.
  std::vector<std::unordered_set<LatticePoint, LatticeHash>> core_of_level;

  const RefineChoice choose = [&](int level, const std::vector<LevelCell>& cells) {
    std::vector<char> want(cells.size(), 0);
    if (progress.cancelled()) return want;
    progress.report("grid", 0.05 + 0.05 * level);
    const double h = size_at(level), far = o.margin * h + o.deflection, cap = 3 * h;
    // This level's corners.
    std::unordered_map<LatticePoint, std::size_t, LatticeHash> index;
    std::vector<Vec3> points;
    std::vector<double> dist;
    std::vector<std::array<std::size_t, 8>> corners(cells.size());
    for (std::size_t c = 0; c < cells.size(); ++c)
      for (int b = 0; b < 8; ++b) {
        const LatticePoint p = {cells[c].origin[0] + cells[c].extent * (b & 1),
                                cells[c].origin[1] + cells[c].extent * ((b >> 1) & 1),
                                cells[c].origin[2] + cells[c].extent * (b >> 2)};
        auto [it, fresh] = index.try_emplace(p, points.size());
        if (fresh) {
          points.push_back(lattice_point(frame, unit, p));
          dist.push_back(distance(p, points.back(), cap));
        }
        corners[c][b] = it->second;
      }
    std::vector<std::pair<std::size_t, std::size_t>> segments;
    for (const auto& cc : corners)
      for (int b = 0; b < 8; ++b)
        for (int bit : {1, 2, 4})
          if (!(b & bit)) segments.push_back({cc[b], cc[b | bit]});
    const std::vector<char> in =
        inside(solid, points, dist, segments, far, o.deflection, out.classifier_calls);
    core_of_level.emplace_back();
    auto& core_here = core_of_level.back();
    std::vector<char> is_core(cells.size(), 0);
    for (std::size_t c = 0; c < cells.size(); ++c) {
      bool all = true;
      for (int b = 0; b < 8 && all; ++b) all = in[corners[c][b]];
      if (all) is_core[c] = 1, core_here.insert(cells[c].origin);
    }
    auto near_core = [&](const LevelCell& c, int lvl, std::int64_t extent, int reach) {
      const auto& set = core_of_level[lvl];
      LatticePoint base = c.origin;
      for (int a = 0; a < 3; ++a) base[a] -= base[a] % extent;
      for (int dz = -reach; dz <= reach; ++dz)
        for (int dy = -reach; dy <= reach; ++dy)
          for (int dx = -reach; dx <= reach; ++dx)
            if (set.count({base[0] + dx * extent, base[1] + dy * extent, base[2] + dz * extent}))
              return true;
      return false;
    };
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (is_core[c]) continue;
      double nearest = std::numeric_limits<double>::infinity();
      for (int b = 0; b < 8; ++b) nearest = std::min(nearest, dist[corners[c][b]]);
      if (nearest >= h) continue;  // the boundary does not pass near
      if (near_core(cells[c], level, cells[c].extent, 2)) continue;
      if (level > 0 && near_core(cells[c], level - 1, 3 * cells[c].extent, 1)) continue;
      want[c] = 1;
    }
    return want;
  };
  out.grid = refine_grid(frame, o.max_level, choose, o.max_cells);
  out.budget_reached = out.grid.budget_reached;
  if (progress.cancelled()) return out;
  const RefinedGrid& g = out.grid;
  const std::size_t nn = g.points.size(), nh = g.hexes.size();

  // The leaves' nodes: distances (capped at three of the finest cells around them).
  std::vector<int> finest(nn, 0);
  for (std::size_t h = 0; h < nh; ++h)
    for (std::int32_t v : g.hexes[h]) finest[v] = std::max<int>(finest[v], g.level[h]);
  std::vector<double> dist(nn);
  for (std::size_t v = 0; v < nn; ++v)
    dist[v] = distance(g.lattice[v], g.points[v], 3 * size_at(finest[v]));
  std::vector<std::pair<std::size_t, std::size_t>> segments;
  for (const Hex& h : g.hexes)
    for (const auto& e : core::kHexEdges)
      segments.push_back({std::size_t(h[e[0]]), std::size_t(h[e[1]])});
  const double finest_far = o.margin * size_at(o.max_level) + o.deflection;
  const std::vector<char> in =
      inside(solid, g.points, dist, segments, finest_far, o.deflection, out.classifier_calls);
  std::vector<char> keep(nh, 0);
  for (std::size_t h = 0; h < nh; ++h) {
    const double far = o.margin * size_at(g.level[h]) + o.deflection;
    bool all = true;
    for (int b = 0; b < 8 && all; ++b) all = in[g.hexes[h][b]] && dist[g.hexes[h][b]] > far;
    keep[h] = all;
  }
  // A manifold boundary: hexahedra at pinched nodes dropped until there are none.
  for (;;) {
    const std::vector<std::int32_t> bad = pinched_nodes(g.hexes, keep);
    if (bad.empty()) break;
    const std::unordered_set<std::int32_t> b(bad.begin(), bad.end());
    for (std::size_t h = 0; h < nh; ++h) {
      if (!keep[h]) continue;
      for (std::int32_t v : g.hexes[h])
        if (b.count(v)) {
          keep[h] = 0, ++out.removed_for_manifold;
          break;
        }
    }
  }
  // The largest face-connected part.
  UnionFind uf(nh);
  std::unordered_map<QuadKey, std::size_t, QuadKeyHash> owner;
  for (std::size_t h = 0; h < nh; ++h)
    if (keep[h])
      for (int f = 0; f < 6; ++f) {
        auto [it, fresh] = owner.try_emplace(quad_key(g.hexes[h], f), h);
        if (!fresh) uf.unite(h, it->second);
      }
  auto corners_of = [&](const Hex& hex) {
    std::array<Vec3, 8> c;
    for (int b = 0; b < 8; ++b) c[b] = g.points[hex[b]];
    return c;
  };
  std::unordered_map<std::size_t, double> part_volume;
  std::vector<double> volume(nh, 0);
  for (std::size_t h = 0; h < nh; ++h)
    if (keep[h])
      volume[h] = quality::hex_volume(corners_of(g.hexes[h])), part_volume[uf.find(h)] += volume[h];
  std::size_t largest = 0;
  double best = -1;
  for (const auto& [root, v] : part_volume)
    if (v > best || (v == best && root < largest)) best = v, largest = root;
  for (std::size_t h = 0; h < nh; ++h) {
    if (!keep[h]) continue;
    if (uf.find(h) != largest) {
      ++out.removed_components, out.left_out_volume += volume[h];
      continue;
    }
    out.core.push_back(g.hexes[h]);
    out.core_volume += volume[h];
    out.levels_used = std::max<int>(out.levels_used, g.level[h]);
  }
  return out;
}

}  // namespace vorohex::grid::detail
