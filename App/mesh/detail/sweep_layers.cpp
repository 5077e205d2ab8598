#include "mesh/detail/sweep_layers.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace vorohex::mesh::detail {

using core::Vec3;

AffineFit::AffineFit(const std::vector<Vec3>& x) {
  cx_ = Vec3::Zero();
  for (const Vec3& p : x) cx_ += p;
  cx_ /= double(x.size());
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  for (const Vec3& p : x) c += (p - cx_) * (p - cx_).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(c);
  n_ = es.eigenvectors().col(0);
  e1_ = es.eigenvectors().col(2);
  e2_ = n_.cross(e1_);
  a_.reserve(x.size());
  Eigen::Matrix2d g = Eigen::Matrix2d::Zero();
  for (const Vec3& p : x) {
    a_.emplace_back((p - cx_).dot(e1_), (p - cx_).dot(e2_));
    g += a_.back() * a_.back().transpose();
  }
  ginv_ = g.inverse();
}

void AffineFit::fit(const std::vector<Vec3>& y) {
  cy_ = Vec3::Zero();
  for (const Vec3& p : y) cy_ += p;
  cy_ /= double(y.size());
  Eigen::Matrix<double, 3, 2> b = Eigen::Matrix<double, 3, 2>::Zero();
  for (std::size_t i = 0; i < y.size(); ++i) b += (y[i] - cy_) * a_[i].transpose();
  m_ = b * ginv_;
  const Vec3 cr = m_.col(0).cross(m_.col(1));
  const double len = cr.norm();
  ny_ = len > 0 ? Vec3(cr / std::sqrt(len)) : Vec3::Zero();
}

Vec3 AffineFit::operator()(const Vec3& p) const {
  const Vec3 d = p - cx_;
  return cy_ + m_ * Eigen::Vector2d(d.dot(e1_), d.dot(e2_)) + d.dot(n_) * ny_;
}

namespace {

// Mean value weights (Floater) of each inner node's neighbours along the quads' sides, on the
// positions x: per quad at node j with sides to u and v at angle a between them, tan(a / 2) /
// |x_u - x_j| to u and tan(a / 2) / |x_v - x_j| to v, normalised. They reproduce x (a flat
// star's centre is its nodes' weighted mean).
std::vector<std::vector<std::pair<int, double>>> mean_value_weights(
    const Vec3* x, std::size_t M, std::size_t nb, const std::vector<std::array<int, 4>>& quads) {
  std::vector<std::vector<std::pair<int, double>>> weights(M);
  auto add = [&](std::size_t j, int u, double w) {
    for (auto& [v, y] : weights[j])
      if (v == u) return void(y += w);
    weights[j].emplace_back(u, w);
  };
  for (const auto& q : quads)
    for (int c = 0; c < 4; ++c) {
      const std::size_t j = std::size_t(q[c]);
      if (j < nb) continue;
      const int u = q[(c + 3) % 4], v = q[(c + 1) % 4];
      const Vec3 a = x[u] - x[j], b = x[v] - x[j];
      const double la = a.norm(), lb = b.norm();
      if (!(la > 0) || !(lb > 0)) continue;
      const double t = std::tan(0.5 * std::atan2(a.cross(b).norm(), a.dot(b)));
      add(j, u, t / la);
      add(j, v, t / lb);
    }
  for (auto& w : weights) {
    double sum = 0;
    for (const auto& [v, y] : w) sum += y;
    if (sum > 0)
      for (auto& [v, y] : w) y /= sum;
    else
      w.clear();
  }
  return weights;
}

}  // namespace

int smooth_layer_interiors(std::vector<Vec3>& P, std::size_t M, std::size_t nb, int first, int last,
                           const std::vector<std::array<int, 4>>& quads, double tolerance,
                           int max_sweeps, const std::function<Vec3(int, const Vec3&)>& onto,
                           const std::function<bool()>& cancelled) {
  // Layer k is layer k - 1 deformed to layer k's boundary in kSteps steps, the boundary moved
  // a step's share each time and the inner nodes put where the mean value weights of the
  // step before (which reproduce it) place them: each step's displacement spreads like a
  // harmonic function from the boundary, on the mesh as the steps before left it. Weights
  // fixed on the source alone compress the thin ring of quads by a hole that grows from 4 to
  // 8 (a countersink) past its width; recomputed step by step they compress it by a factor
  // per step. Uniform weights pull the nodes by a hole into it (the mean of two rim nodes
  // lies inside the circle).
  constexpr int kSteps = 4;
  int slowest = 0;
  std::vector<Vec3> cur(M), from(M);
  for (int k = std::max(first, 1); k <= last; ++k) {
    Vec3* layer = P.data() + std::size_t(k) * M;
    const Vec3* below = P.data() + std::size_t(k - 1) * M;
    std::copy(below, below + M, cur.begin());
    from = cur;
    for (int step = 1; step <= kSteps; ++step) {
      if (cancelled && cancelled()) return -1;
      const auto weights = mean_value_weights(cur.data(), M, nb, quads);
      const double w = double(step) / kSteps;
      for (std::size_t j = 0; j < nb; ++j) cur[j] = (1 - w) * from[j] + w * layer[j];
      const bool last_step = step == kSteps;
      int sweeps = 0;
      for (; sweeps < max_sweeps; ++sweeps) {  // Gauss-Seidel
        double moved = 0;
        for (std::size_t j = nb; j < M; ++j) {
          if (weights[j].empty()) continue;
          Vec3 mean = Vec3::Zero();
          for (const auto& [v, y] : weights[j]) mean += y * cur[v];
          if (last_step && onto) mean = onto(k, mean);
          moved = std::max(moved, (mean - cur[j]).norm());
          cur[j] = mean;
        }
        if (moved <= tolerance) break;
      }
      slowest = std::max(slowest, sweeps);
    }
    std::copy(cur.begin() + nb, cur.end(), layer + nb);
  }
  return slowest;
}

}  // namespace vorohex::mesh::detail
