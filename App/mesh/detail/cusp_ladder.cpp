#include "mesh/detail/cusp_ladder.h"

#include <algorithm>
#include <cmath>

namespace vorohex::mesh::detail {

namespace {

// Interior angles below this (radians, about 9 degrees) are points a ladder starts at.
constexpr double kTip = 0.15;
// Two loops touching at a point are joined there when both angles are below this (about 30
// degrees; the point spacing may have opened them beyond kTip).
constexpr double kTouch = 0.5;
// A ladder ends once its rung is this long (x size): the rest is wide enough for the lattice.
constexpr double kWide = 0.4;

double cross2(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// The angle inside the domain (on the loop's left) at `at`, in [0, 2 pi).
double interior_angle(const Vec2& prev, const Vec2& at, const Vec2& next) {
  const Vec2 a = prev - at, b = next - at;
  double t = std::atan2(cross2(b, a), b.dot(a));
  if (t < 0) t += 2 * M_PI;
  return t;
}

bool proper_cross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross2(b - a, c - a), d2 = cross2(b - a, d - a);
  const double d3 = cross2(d - c, a - c), d4 = cross2(d - c, b - c);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

struct Peeler {
  const std::vector<Vec2>& p;              // every given node
  std::vector<std::vector<int>>& loops;    // the loops left, as node indices
  std::vector<std::array<int, 4>>& quads;  // the ladders' quads
  double size;

  int at(const std::vector<int>& l, long k) const {
    const long n = long(l.size());
    return l[std::size_t(((k % n) + n) % n)];
  }

  // Whether the quad's new rung (w[0] to w[3]) crosses a boundary segment, or another
  // boundary node lies inside the quad.
  bool blocked(const std::array<int, 4>& w) const {
    for (const auto& l : loops)
      for (std::size_t k = 0; k < l.size(); ++k) {
        const int a = l[k], b = l[(k + 1) % l.size()];
        if (a != w[0] && a != w[3] && b != w[0] && b != w[3] &&
            proper_cross(p[w[0]], p[w[3]], p[a], p[b]))
          return true;
        if (std::find(w.begin(), w.end(), a) != w.end()) continue;
        bool inside = true;
        for (int i = 0; i < 4 && inside; ++i)
          inside = cross2(p[w[(i + 1) % 4]] - p[w[i]], p[a] - p[w[i]]) > 0;
        if (inside) return true;
      }
    return false;
  }

  // The best quad of four consecutive nodes of loop l starting at one of `starts` (loop
  // positions), its two middle nodes peeled off; false when none is valid or the loop would
  // get too short.
  bool peel(std::size_t l, const std::vector<long>& starts, long* rung_at) {
    std::vector<int>& loop = loops[l];
    const std::size_t least = loops.size() == 1 ? 4 : 6;
    if (loop.size() < least + 2) return false;
    double best = 0;
    long chosen = 0;
    bool found = false;
    std::array<int, 4> quad{};
    for (long s : starts) {
      const std::array<int, 4> w{at(loop, s), at(loop, s + 1), at(loop, s + 2), at(loop, s + 3)};
      const double q = quad_quality(p[w[0]], p[w[1]], p[w[2]], p[w[3]]);
      if (q > best && !blocked(w)) best = q, chosen = s, quad = w, found = true;
    }
    if (!found) return false;
    quads.push_back(quad);
    const long n = long(loop.size());
    const long a = ((chosen + 1) % n + n) % n, b = (a + 1) % n;
    // Erase the two middle nodes (the later position first).
    loop.erase(loop.begin() + std::max(a, b));
    loop.erase(loop.begin() + std::min(a, b));
    // The rung: quad[0] and quad[3], now neighbours.
    const auto it = std::find(loop.begin(), loop.end(), quad[0]);
    *rung_at = long(it - loop.begin());
    return true;
  }

  // A ladder from the point at position i of loop l. Returns whether a quad was peeled.
  bool ladder(std::size_t l, long i) {
    long rung = 0;
    if (!peel(l, {i - 2, i - 1}, &rung)) return false;
    for (;;) {
      const std::vector<int>& loop = loops[l];
      const int x = at(loop, rung), y = at(loop, rung + 1);
      if ((p[x] - p[y]).norm() >= kWide * size) break;
      if (!peel(l, {rung - 2, rung - 1, rung}, &rung)) break;
    }
    return true;
  }
};

// Two loops that touch at a point where both come to a point (a hole tangent to the outline
// from inside: the crescent between a plate's round outline and a boss's circle tangent to
// it) are joined there into one loop that passes the point twice, each time as a point a
// ladder starts at (whatever its angle); the ladders then take both copies of the node away.
// (The triangulation cannot take two loops through one point.)
void join_touching_loops(const std::vector<Vec2>& p, double tie,
                         std::vector<std::vector<int>>& loops, std::vector<char>& joined) {
  auto node = [](const std::vector<int>& l, std::size_t k) { return l[k % l.size()]; };
  for (std::size_t a = 0; a < loops.size(); ++a)
    for (std::size_t b = a + 1; b < loops.size(); ++b) {
      const std::vector<int>&la = loops[a], &lb = loops[b];
      for (std::size_t i = 0; i < la.size(); ++i)
        for (std::size_t j = 0; j < lb.size(); ++j) {
          if ((p[la[i]] - p[lb[j]]).norm() > tie) continue;
          const std::size_t na = la.size(), nb = lb.size();
          // Into the point along a, out along b; later into it along b, out along a.
          const double first =
              interior_angle(p[node(la, i + na - 1)], p[la[i]], p[node(lb, j + 1)]);
          const double second =
              interior_angle(p[node(lb, j + nb - 1)], p[lb[j]], p[node(la, i + 1)]);
          if (first >= kTouch || second >= kTouch) continue;
          std::vector<int> spliced(la.begin(), la.begin() + long(i) + 1);
          for (std::size_t k = 1; k <= nb; ++k) spliced.push_back(node(lb, j + k));
          spliced.insert(spliced.end(), la.begin() + long(i) + 1, la.end());
          joined[std::size_t(la[i])] = joined[std::size_t(lb[j])] = 1;
          loops[a] = std::move(spliced);
          loops.erase(loops.begin() + long(b));
          return join_touching_loops(p, tie, loops, joined);  // at most once per pair of loops
        }
    }
}

}  // namespace

CuspLadders cusp_ladders(const std::vector<std::vector<Vec2>>& loops, double size) {
  CuspLadders out;
  std::vector<Vec2> p;
  std::vector<std::vector<int>> left;
  for (const auto& loop : loops) {
    left.emplace_back();
    for (const Vec2& q : loop) {
      left.back().push_back(int(p.size()));
      p.push_back(q);
    }
  }
  double extent = 0;
  for (const Vec2& q : p) extent = std::max(extent, q.lpNorm<Eigen::Infinity>());
  const double tie = 1e-9 * std::max(extent, 1.0);
  std::vector<char> joined(p.size(), 0);  // nodes where two loops were joined
  join_touching_loops(p, tie, left, joined);
  Peeler peeler{p, left, out.quads, size};
  if (size > 0)
    for (std::size_t l = 0; l < left.size(); ++l) {
      // Each ladder changes the loop: look again from the start until no point is left.
      for (bool again = true; again;) {
        again = false;
        const std::vector<int>& loop = left[l];
        const long n = long(loop.size());
        for (long i = 0; i < n && !again; ++i) {
          const double angle = interior_angle(p[peeler.at(loop, i - 1)], p[loop[std::size_t(i)]],
                                              p[peeler.at(loop, i + 1)]);
          if ((angle < kTip || joined[std::size_t(loop[std::size_t(i)])]) && peeler.ladder(l, i))
            again = true;
        }
      }
    }
  for (const auto& l : left) {
    out.loops.emplace_back();
    for (int k : l) out.loops.back().push_back(p[std::size_t(k)]);
  }
  out.index = std::move(left);
  return out;
}

}  // namespace vorohex::mesh::detail
