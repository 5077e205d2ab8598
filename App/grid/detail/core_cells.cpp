#include "grid/detail/core_cells.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include "occ/classify_points.h"

namespace vorohex::grid::detail {
namespace {

using core::Vec3;

// Index range of lines within [lo, hi].
std::pair<int, int> line_range(const std::vector<double>& lines, double lo, double hi) {
  const int a = int(std::lower_bound(lines.begin(), lines.end(), lo) - lines.begin());
  const int b = int(std::upper_bound(lines.begin(), lines.end(), hi) - lines.begin()) - 1;
  return {a, b};
}

// The 2x2x2 cells around a grid node: is the boundary of the core there a disc (or empty)?
// It is when the core cells and the other cells among the eight are each face-connected.
bool manifold_at(const CoreCells& c, int i, int j, int k, std::array<int, 8>* component = nullptr) {
  std::array<char, 8> in{};
  for (int b = 0; b < 8; ++b)
    in[b] = c.at(i - 1 + (b & 1), j - 1 + ((b >> 1) & 1), k - 1 + (b >> 2));
  std::array<int, 8> comp;
  comp.fill(-1);
  int components[2] = {0, 0};
  for (int s = 0; s < 8; ++s) {
    if (comp[s] >= 0) continue;
    comp[s] = components[int(in[s])]++ * 2 + int(in[s]);
    std::array<int, 8> stack{};
    int top = 0;
    stack[top++] = s;
    while (top) {
      const int x = stack[--top];
      for (int bit : {1, 2, 4}) {
        const int y = x ^ bit;
        if (comp[y] < 0 && in[y] == in[x]) comp[y] = comp[x], stack[top++] = y;
      }
    }
  }
  if (component) *component = comp;
  return components[0] <= 1 && components[1] <= 1;
}

}  // namespace

// Distance from p to triangle abc (closest point by the Voronoi regions of the triangle).
double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + ab * (d1 / (d1 - d3)))).norm();
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + ac * (d2 / (d2 - d6)))).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm();
  const double denom = va + vb + vc;
  if (!(std::abs(denom) > 0)) return std::min({ap.norm(), bp.norm(), cp.norm()});
  const double v = vb / denom, w = vc / denom;
  return (p - (a + ab * v + ac * w)).norm();
}

std::vector<char> vote_inside(const occ::Solid& solid, UnionFind& uf,
                              const std::vector<double>& dist, double far,
                              const std::function<Vec3(std::size_t)>& point, double tolerance,
                              std::size_t& calls) {
  const std::size_t n = dist.size();
  // Representatives: up to three per set (the farthest from the boundary), majority vote.
  std::vector<std::vector<std::size_t>> reps(n);
  for (std::size_t a = 0; a < n; ++a) {
    if (dist[a] <= far) continue;
    auto& r = reps[uf.find(a)];
    r.push_back(a);
    std::sort(r.begin(), r.end(), [&](std::size_t x, std::size_t y) { return dist[x] > dist[y]; });
    if (r.size() > 3) r.pop_back();
  }
  std::vector<Vec3> query;
  std::vector<std::size_t> owner;
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t r : reps[a]) query.push_back(point(r)), owner.push_back(a);
  const std::vector<occ::PointState> states = occ::classify_points(solid, query, tolerance);
  calls += query.size();
  std::vector<int> votes(n, 0);
  for (std::size_t q = 0; q < query.size(); ++q)
    votes[owner[q]] += states[q] == occ::PointState::inside    ? 1
                       : states[q] == occ::PointState::outside ? -1
                                                               : 0;
  std::vector<char> out(n, 0);
  for (std::size_t a = 0; a < n; ++a) out[a] = dist[a] > far && votes[uf.find(a)] > 0;
  return out;
}

std::vector<double> node_distances(const GridFrame& frame, const occ::Tessellation& t, double cap) {
  const int n0 = frame.nodes(0), n1 = frame.nodes(1), n2 = frame.nodes(2);
  std::vector<double> d(std::size_t(n0) * n1 * n2, cap);
  for (const occ::FaceTriangulation& f : t.faces) {
    std::vector<Vec3> q(f.nodes.size());
    for (std::size_t i = 0; i < q.size(); ++i) q[i] = frame.to_frame(f.nodes[i]);
    for (const auto& tri : f.triangles) {
      const Vec3 &a = q[tri[0]], &b = q[tri[1]], &c = q[tri[2]];
      const Vec3 lo = a.cwiseMin(b).cwiseMin(c).array() - cap;
      const Vec3 hi = a.cwiseMax(b).cwiseMax(c).array() + cap;
      const auto [i0, i1] = line_range(frame.lines[0], lo.x(), hi.x());
      const auto [j0, j1] = line_range(frame.lines[1], lo.y(), hi.y());
      const auto [k0, k1] = line_range(frame.lines[2], lo.z(), hi.z());
      for (int k = k0; k <= k1; ++k)
        for (int j = j0; j <= j1; ++j)
          for (int i = i0; i <= i1; ++i) {
            const Vec3 p(frame.lines[0][i], frame.lines[1][j], frame.lines[2][k]);
            double& di = d[std::size_t(i) + std::size_t(n0) * (j + std::size_t(n1) * k)];
            di = std::min(di, point_triangle_distance(p, a, b, c));
          }
    }
  }
  return d;
}

CoreCells core_cells(const GridFrame& frame, const occ::Solid& solid, const occ::Tessellation& t,
                     double size, double margin, double deflection) {
  const int n0 = frame.nodes(0), n1 = frame.nodes(1), n2 = frame.nodes(2);
  auto node = [&](int i, int j, int k) {
    return std::size_t(i) + std::size_t(n0) * (std::size_t(j) + std::size_t(n1) * k);
  };
  const double cap = 3 * size;
  const std::vector<double> dist = node_distances(frame, t, cap);
  // Far nodes: farther than the margin from the boundary (the tessellation's chord error
  // added). Two far nodes joined by a grid edge shorter than the sum of their distances lie
  // on the same side of the boundary, so one classification per connected set suffices.
  const double far = margin * size + deflection;
  const std::size_t nn = dist.size();
  UnionFind uf(nn);
  for (int k = 0; k < n2; ++k)
    for (int j = 0; j < n1; ++j)
      for (int i = 0; i < n0; ++i) {
        const std::size_t a = node(i, j, k);
        if (dist[a] <= far) continue;
        const int ijk[3] = {i, j, k};
        for (int ax = 0; ax < 3; ++ax) {
          if (ijk[ax] + 1 >= frame.nodes(ax)) continue;
          int nb[3] = {i, j, k};
          ++nb[ax];
          const std::size_t b = node(nb[0], nb[1], nb[2]);
          const double len = frame.lines[ax][ijk[ax] + 1] - frame.lines[ax][ijk[ax]];
          if (dist[b] > far && dist[a] + dist[b] > len + 2 * deflection) uf.unite(a, b);
        }
      }
  std::size_t calls = 0;
  const std::vector<char> in = vote_inside(
      solid, uf, dist, far,
      [&](std::size_t r) {
        return frame.point(int(r % n0), int((r / n0) % n1), int(r / (std::size_t(n0) * n1)));
      },
      std::max(solid.tolerance(), 1e-9 * size), calls);
  CoreCells c;
  c.classifier_calls = calls;
  c.cells = {frame.cells(0), frame.cells(1), frame.cells(2)};
  c.in_core.assign(std::size_t(c.cells[0]) * c.cells[1] * c.cells[2], 0);
  for (int k = 0; k < c.cells[2]; ++k)
    for (int j = 0; j < c.cells[1]; ++j)
      for (int i = 0; i < c.cells[0]; ++i) {
        bool all = true;
        for (int b = 0; b < 8 && all; ++b)
          all = in[node(i + (b & 1), j + ((b >> 1) & 1), k + (b >> 2))];
        c.in_core[c.index(i, j, k)] = all;
      }

  // Manifold: where the cells around a node are pinched, drop core cells (never add, so
  // the core stays inside) until every node is fine.
  for (bool changed = true; changed;) {
    changed = false;
    for (int k = 0; k < n2; ++k)
      for (int j = 0; j < n1; ++j)
        for (int i = 0; i < n0; ++i) {
          std::array<int, 8> comp;
          if (manifold_at(c, i, j, k, &comp)) continue;
          // Keep the in-cells of component 1 (the first core component) if the outside is
          // connected; otherwise drop all core cells here.
          bool out_connected = true;
          for (int b = 0; b < 8; ++b)
            out_connected = out_connected && (comp[b] & 1 || comp[b] == 0);
          for (int b = 0; b < 8; ++b) {
            const int ci = i - 1 + (b & 1), cj = j - 1 + ((b >> 1) & 1), ck = k - 1 + (b >> 2);
            if (!c.at(ci, cj, ck)) continue;
            if (out_connected && comp[b] == 1) continue;
            c.in_core[c.index(ci, cj, ck)] = 0;
            ++c.removed_for_manifold;
            changed = true;
          }
        }
  }

  // Largest face-connected component.
  const std::size_t nc = c.in_core.size();
  std::vector<int> label(nc, -1);
  std::vector<std::size_t> sizes;
  for (std::size_t s = 0; s < nc; ++s) {
    if (!c.in_core[s] || label[s] >= 0) continue;
    const int l = int(sizes.size());
    sizes.push_back(0);
    std::vector<std::size_t> stack{s};
    label[s] = l;
    while (!stack.empty()) {
      const std::size_t x = stack.back();
      stack.pop_back();
      ++sizes[l];
      const int i = int(x % c.cells[0]), j = int((x / c.cells[0]) % c.cells[1]),
                k = int(x / (std::size_t(c.cells[0]) * c.cells[1]));
      const int nb[6][3] = {{i - 1, j, k}, {i + 1, j, k}, {i, j - 1, k},
                            {i, j + 1, k}, {i, j, k - 1}, {i, j, k + 1}};
      for (const auto& q : nb) {
        if (!c.at(q[0], q[1], q[2])) continue;
        const std::size_t y = c.index(q[0], q[1], q[2]);
        if (label[y] < 0) label[y] = l, stack.push_back(y);
      }
    }
  }
  const int keep =
      sizes.empty() ? -1 : int(std::max_element(sizes.begin(), sizes.end()) - sizes.begin());
  for (std::size_t s = 0; s < nc; ++s)
    if (c.in_core[s] && label[s] != keep) c.in_core[s] = 0, ++c.removed_components;
  c.core = keep < 0 ? 0 : sizes[keep];
  return c;
}

}  // namespace vorohex::grid::detail
