#include "smooth/detail/hex_jacobian.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "smooth/detail/topology.h"

namespace vorohex::smooth::detail {
namespace {

using core::Vec3;

// The 12 edges of a VTK hex as (from, to).
constexpr int kEdges[12][2] = {{0, 1}, {1, 2}, {3, 2}, {0, 3}, {4, 5}, {5, 6},
                               {7, 6}, {4, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

// For corner c and frame vector j (towards kCornerNeighbours[c][j]): the edge index and
// whether the frame vector is the edge reversed.
struct FrameEdges {
  int edge[8][3];
  bool reversed[8][3];
};

constexpr FrameEdges make_frame_edges() {
  FrameEdges f{};
  for (int c = 0; c < 8; ++c)
    for (int j = 0; j < 3; ++j) {
      const int n = kCornerNeighbours[c][j];
      for (int e = 0; e < 12; ++e) {
        if (kEdges[e][0] == c && kEdges[e][1] == n) f.edge[c][j] = e, f.reversed[c][j] = false;
        if (kEdges[e][0] == n && kEdges[e][1] == c) f.edge[c][j] = e, f.reversed[c][j] = true;
      }
    }
  return f;
}

constexpr FrameEdges kFrame = make_frame_edges();

// Collapsed edge ratio of quality::scaled_jacobian (squared lengths).
constexpr double kCollapsedRatio2 = 1e-30;

}  // namespace

std::array<double, 9> hex_frame_jacobians(const std::array<Vec3, 8>& p) {
  std::array<double, 9> out{};
  Vec3 e[12];
  double len2[12];
  double max_len2 = 0;
  for (int i = 0; i < 12; ++i) {
    e[i] = p[kEdges[i][1]] - p[kEdges[i][0]];
    len2[i] = e[i].squaredNorm();
    max_len2 = std::max(max_len2, len2[i]);
  }
  const Vec3 axes[3] = {(p[1] - p[0]) + (p[2] - p[3]) + (p[5] - p[4]) + (p[6] - p[7]),
                        (p[3] - p[0]) + (p[2] - p[1]) + (p[7] - p[4]) + (p[6] - p[5]),
                        (p[4] - p[0]) + (p[5] - p[1]) + (p[6] - p[2]) + (p[7] - p[3])};
  const double axis2[3] = {axes[0].squaredNorm(), axes[1].squaredNorm(), axes[2].squaredNorm()};
  for (double a : axis2) max_len2 = std::max(max_len2, a);
  if (!(max_len2 > 0) || !std::isfinite(max_len2)) return out;
  const double tiny = kCollapsedRatio2 * max_len2;
  for (double l : len2)
    if (!(l > tiny)) return out;
  for (double l : axis2)
    if (!(l > tiny)) return out;

  out[0] = axes[0].dot(axes[1].cross(axes[2])) / std::sqrt(axis2[0] * axis2[1] * axis2[2]);
  for (int c = 0; c < 8; ++c) {
    const int* ed = kFrame.edge[c];
    const bool* rev = kFrame.reversed[c];
    // Negation is exact, so flipping signs afterwards equals using the reversed vectors.
    double det = e[ed[0]].dot(e[ed[1]].cross(e[ed[2]]));
    if ((rev[0] != rev[1]) != rev[2]) det = -det;  // an odd number of reversed vectors
    out[c + 1] = det / std::sqrt(len2[ed[0]] * len2[ed[1]] * len2[ed[2]]);
  }
  return out;
}

double hex_scaled_jacobian(const std::array<Vec3, 8>& p) {
  const std::array<double, 9> v = hex_frame_jacobians(p);
  return std::clamp(*std::min_element(v.begin(), v.end()), -1.0, 1.0);
}

}  // namespace vorohex::smooth::detail
