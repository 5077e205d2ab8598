#include "smooth/detail/node_objective.h"

#include <Eigen/Cholesky>
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

namespace vorohex::smooth::detail {

namespace {
// Sign of each VTK corner in the three centre axes of quality::scaled_jacobian.
constexpr int kAxisSign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                 {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
}  // namespace

std::vector<AffineFrame> affine_frames(const std::vector<IncidentHex>& hexes, const Vec3& x) {
  std::vector<AffineFrame> frames;
  frames.reserve(hexes.size() * 5);
  for (const auto& hex : hexes) {
    const int c = hex.corner;
    auto point = [&](int i) -> const Vec3& { return i == c ? x : hex.points[i]; };
    const int corners[4] = {c, kCornerNeighbours[c][0], kCornerNeighbours[c][1],
                            kCornerNeighbours[c][2]};
    for (int k : corners) {
      const Vec3& p = point(k);
      const Vec3 e[3] = {point(kCornerNeighbours[k][0]) - p, point(kCornerNeighbours[k][1]) - p,
                         point(kCornerNeighbours[k][2]) - p};
      const Vec3 cof[3] = {e[1].cross(e[2]), e[2].cross(e[0]), e[0].cross(e[1])};
      AffineFrame f;
      f.value = e[0].dot(cof[0]);
      f.weight = e[0].norm() * e[1].norm() * e[2].norm();
      if (k == c) {
        f.gradient = -(cof[0] + cof[1] + cof[2]);
      } else {
        for (int j = 0; j < 3; ++j)
          if (kCornerNeighbours[k][j] == c) f.gradient = cof[j];
      }
      frames.push_back(f);
    }
    std::array<Vec3, 8> p;
    for (int i = 0; i < 8; ++i) p[i] = point(i);
    const Vec3 a[3] = {(p[1] - p[0]) + (p[2] - p[3]) + (p[5] - p[4]) + (p[6] - p[7]),
                       (p[3] - p[0]) + (p[2] - p[1]) + (p[7] - p[4]) + (p[6] - p[5]),
                       (p[4] - p[0]) + (p[5] - p[1]) + (p[6] - p[2]) + (p[7] - p[3])};
    const Vec3 cof[3] = {a[1].cross(a[2]), a[2].cross(a[0]), a[0].cross(a[1])};
    AffineFrame f;
    f.value = a[0].dot(cof[0]);
    f.weight = a[0].norm() * a[1].norm() * a[2].norm();
    for (int j = 0; j < 3; ++j) f.gradient += kAxisSign[c][j] * cof[j];
    frames.push_back(f);
  }
  for (auto& f : frames)
    if (!(f.weight > 0)) f.weight = 1;  // a collapsed frame: still push its determinant up
  return frames;
}

double untangle_value(const std::vector<AffineFrame>& frames, const Vec3& d, double b) {
  double u = 0;
  for (const auto& f : frames) {
    const double r = b - (f.value + f.gradient.dot(d)) / f.weight;
    if (r > 0) u += r * r;
  }
  return u;
}

Vec3 untangle_step(const std::vector<AffineFrame>& frames, double b,
                   const Eigen::Matrix<double, 3, Eigen::Dynamic>& basis, double max_step) {
  const Eigen::Index k = basis.cols();
  Vec3 d = Vec3::Zero();
  double u = untangle_value(frames, d, b);
  for (int iter = 0; iter < 10 && u > 0; ++iter) {
    Eigen::MatrixXd h = Eigen::MatrixXd::Zero(k, k);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(k);
    for (const auto& f : frames) {
      const double r = b - (f.value + f.gradient.dot(d)) / f.weight;
      if (r <= 0) continue;
      const Eigen::VectorXd g = basis.transpose() * f.gradient / f.weight;
      h += g * g.transpose();
      rhs += r * g;
    }
    h.diagonal().array() += 1e-9 * (h.trace() + 1e-300);
    Eigen::VectorXd z = h.ldlt().solve(rhs);
    if (!z.allFinite()) return d;
    Vec3 inc = basis * z;
    bool improved = false;
    for (int tries = 0; tries < 30; ++tries, inc *= 0.5) {
      Vec3 trial = d + inc;
      const double len = trial.norm();
      if (len > max_step) trial *= max_step / len;
      const double v = untangle_value(frames, trial, b);
      if (v < u) {
        d = trial;
        u = v;
        improved = true;
        break;
      }
    }
    if (!improved) break;
  }
  return d;
}

}  // namespace vorohex::smooth::detail
