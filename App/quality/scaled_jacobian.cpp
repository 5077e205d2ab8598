#include "quality/scaled_jacobian.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "quality/detail/parallel.h"
#include "quality/detail/scaled_jacobian_terms.h"

namespace vorohex::quality {
namespace {

using core::Vec3;

// For each corner of a VTK hex, its three neighbours ordered so that the edge vectors
// (n0 - c, n1 - c, n2 - c) form a right-handed frame on the reference cube (det = +1).
constexpr int kCornerNeighbours[8][3] = {
    {1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7}, {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3},
};

// Squared lengths below this fraction of the largest one count as a collapsed edge
// (a length ratio of 1e-15: the relative form of Verdict's VERDICT_DBL_MIN test).
constexpr double kCollapsedRatio2 = 1e-30;

double det3(const Vec3& a, const Vec3& b, const Vec3& c) {
  return a.dot(b.cross(c));
}

}  // namespace

namespace detail {

JacobianTerms scaled_jacobian_terms(const std::array<Vec3, 8>& p) {
  // 8 corner frames and the centre frame (principal axes: sums of opposite-face differences).
  std::array<std::array<Vec3, 3>, 9> frames;
  for (int c = 0; c < 8; ++c)
    for (int k = 0; k < 3; ++k) frames[c][k] = p[kCornerNeighbours[c][k]] - p[c];
  frames[8][0] = (p[1] - p[0]) + (p[2] - p[3]) + (p[5] - p[4]) + (p[6] - p[7]);
  frames[8][1] = (p[3] - p[0]) + (p[2] - p[1]) + (p[7] - p[4]) + (p[6] - p[5]);
  frames[8][2] = (p[4] - p[0]) + (p[5] - p[1]) + (p[6] - p[2]) + (p[7] - p[3]);

  std::array<std::array<double, 3>, 9> len2;
  double max_len2 = 0;
  for (int f = 0; f < 9; ++f)
    for (int k = 0; k < 3; ++k) {
      len2[f][k] = frames[f][k].squaredNorm();
      max_len2 = std::max(max_len2, len2[f][k]);
    }
  JacobianTerms t;
  // NaN or infinite coordinates fail this test too: an element we cannot measure is invalid.
  if (!(max_len2 > 0) || !std::isfinite(max_len2)) {
    t.collapsed = true;
    return t;
  }
  const double tiny = kCollapsedRatio2 * max_len2;
  for (int f = 0; f < 9; ++f) {
    const double l0 = len2[f][0], l1 = len2[f][1], l2 = len2[f][2];
    if (!(l0 > tiny) || !(l1 > tiny) || !(l2 > tiny)) {
      t.collapsed = true;  // this frame's determinant stays 0
      continue;
    }
    t.det[f] = det3(frames[f][0], frames[f][1], frames[f][2]) / std::sqrt(l0 * l1 * l2);
  }
  return t;
}

}  // namespace detail

double scaled_jacobian(const std::array<Vec3, 8>& corners) {
  const detail::JacobianTerms t = detail::scaled_jacobian_terms(corners);
  if (t.collapsed) return 0;  // Verdict says DBL_MAX; a collapsed edge is invalid, not perfect
  const double m = *std::min_element(t.det.begin(), t.det.end());
  return std::clamp(m, -1.0, 1.0);
}

std::vector<double> scaled_jacobians(const core::HexMesh& mesh) {
  std::vector<double> values(mesh.num_hexes());
  const auto& points = mesh.points();
  const auto& hexes = mesh.hexes();
  // Threads pay off only for large meshes; each gets one contiguous chunk.
  detail::parallel_chunks(values.size(), 20000, [&](std::size_t, std::size_t b, std::size_t e) {
    std::array<Vec3, 8> corners;
    for (std::size_t h = b; h < e; ++h) {
      for (int i = 0; i < 8; ++i) corners[i] = points[hexes[h][i]];
      values[h] = scaled_jacobian(corners);
    }
  });
  return values;
}

double hex_volume(const std::array<Vec3, 8>& p) {
  // Divergence theorem over the six bilinear faces: the flux of x through a bilinear patch
  // a-b-c-d is exactly (a + b + c + d) . ((c - a) x (d - b)) / 8, so V = sum / 24 with no
  // quadrature error (equal to 2x2x2 Gauss of det J). Coordinates relative to node 0 keep
  // rounding independent of where the element sits.
  std::array<Vec3, 8> q;
  for (int i = 0; i < 8; ++i) q[i] = p[i] - p[0];
  double sum = 0;
  for (const auto& f : core::kHexFaces) {
    const Vec3 &a = q[f[0]], &b = q[f[1]], &c = q[f[2]], &d = q[f[3]];
    sum += (a + b + c + d).dot((c - a).cross(d - b));
  }
  return sum / 24.0;
}

}  // namespace vorohex::quality
