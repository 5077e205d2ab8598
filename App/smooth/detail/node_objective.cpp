#include "smooth/detail/node_objective.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "smooth/detail/topology.h"

namespace vorohex::smooth::detail {
namespace {

using core::Vec3;

// Accumulates one hex's corners whose frame contains its local corner `c` (placed at x).
template <bool kGradient>
void accumulate(const IncidentHex& hex, const Vec3& x, double delta, ObjectiveValue& out,
                int& edges) {
  const int c = hex.corner;
  auto point = [&](int i) -> const Vec3& { return i == c ? x : hex.points[i]; };
  const int corners[4] = {c, kCornerNeighbours[c][0], kCornerNeighbours[c][1],
                          kCornerNeighbours[c][2]};
  const double four_d2 = 4 * delta * delta;
  for (int k : corners) {
    const Vec3& p = point(k);
    const Vec3 e[3] = {point(kCornerNeighbours[k][0]) - p, point(kCornerNeighbours[k][1]) - p,
                       point(kCornerNeighbours[k][2]) - p};
    const Vec3 cof[3] = {e[1].cross(e[2]), e[2].cross(e[0]), e[0].cross(e[1])};
    const double sigma = e[0].dot(cof[0]);
    const double f = e[0].squaredNorm() + e[1].squaredNorm() + e[2].squaredNorm();
    const double root = std::sqrt(sigma * sigma + four_d2);
    const double h = 0.5 * (sigma + root);
    out.min_det = std::min(out.min_det, sigma);
    if (kGradient) {
      out.mean_edge += std::sqrt(e[0].squaredNorm()) + std::sqrt(e[1].squaredNorm()) +
                       std::sqrt(e[2].squaredNorm());
      edges += 3;
    }
    if (!(h > 0)) {  // delta = 0 and an inverted or flat corner: outside the domain
      out.value = std::numeric_limits<double>::infinity();
      continue;
    }
    const double h23 = std::cbrt(h * h);
    out.value += f / (3 * h23);
    if (!kGradient || !std::isfinite(out.value)) continue;
    // d/dA of |A|^2 / (3 h^(2/3)) = 2A / (3 h^(2/3)) - 2 |A|^2 h' / (9 h^(5/3)) cof(A).
    const double dh = h / root;
    const double a = 2 / (3 * h23);
    const double b = 2 * f * dh / (9 * h23 * h);
    Vec3 g[3];
    for (int j = 0; j < 3; ++j) g[j] = a * e[j] - b * cof[j];
    if (k == c) {
      out.gradient -= g[0] + g[1] + g[2];
    } else {
      for (int j = 0; j < 3; ++j)
        if (kCornerNeighbours[k][j] == c) out.gradient += g[j];
    }
  }
}

}  // namespace

ObjectiveValue node_objective(const std::vector<IncidentHex>& hexes, const Vec3& x, double delta) {
  ObjectiveValue out;
  out.min_det = std::numeric_limits<double>::infinity();
  int edges = 0;
  for (const auto& hex : hexes) accumulate<true>(hex, x, delta, out, edges);
  if (edges > 0) out.mean_edge /= edges;
  if (!std::isfinite(out.value)) out.gradient.setZero();
  return out;
}

double node_objective_value(const std::vector<IncidentHex>& hexes, const Vec3& x, double delta) {
  ObjectiveValue out;
  out.min_det = std::numeric_limits<double>::infinity();
  int edges = 0;
  for (const auto& hex : hexes) accumulate<false>(hex, x, delta, out, edges);
  return out.value;
}

double choose_delta(double min_det, double mean_edge) {
  // Escobar et al.: delta^2 = eps (eps - min_det) when min_det < eps, else 0, with eps a
  // small fraction of the typical corner volume.
  const double eps = 1e-2 * mean_edge * mean_edge * mean_edge;
  if (!(min_det < eps)) return 0;
  return std::sqrt(eps * (eps - min_det));
}

}  // namespace vorohex::smooth::detail
