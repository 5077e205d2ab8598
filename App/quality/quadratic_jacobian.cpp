#include "quality/quadratic_jacobian.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/hex_mesh.h"

namespace vorohex::quality {
namespace {

// Reference coordinates of the 20 nodes: VTK corners, then the midpoints of kHexEdges.
std::array<Eigen::Vector3d, 20> reference_nodes() {
  std::array<Eigen::Vector3d, 20> r;
  const int sign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                          {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  for (int i = 0; i < 8; ++i) r[i] = Eigen::Vector3d(sign[i][0], sign[i][1], sign[i][2]);
  for (int e = 0; e < 12; ++e)
    r[8 + e] = (r[core::kHexEdges[e][0]] + r[core::kHexEdges[e][1]]) / 2.0;
  return r;
}

// Gradient of node i's serendipity shape function at reference point p.
Eigen::Vector3d shape_gradient(const Eigen::Vector3d& node, const Eigen::Vector3d& p) {
  Eigen::Vector3d g;
  int zero = -1;
  for (int k = 0; k < 3; ++k)
    if (node[k] == 0) zero = k;
  if (zero < 0) {  // corner: N = 1/8 prod(1 + x_k n_k) (sum x_k n_k - 2)
    const Eigen::Vector3d a = Eigen::Vector3d::Ones() + p.cwiseProduct(node);
    const double s = p.dot(node);
    for (int k = 0; k < 3; ++k) {
      const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      g[k] = 0.125 * node[k] * a[k1] * a[k2] * (s - 2 + a[k]);
    }
    return g;
  }
  // Mid-edge node on the axis `zero`: N = 1/4 (1 - x_z^2) prod_{k != z} (1 + x_k n_k).
  const int k1 = (zero + 1) % 3, k2 = (zero + 2) % 3;
  const double b = 1 + p[k1] * node[k1], c = 1 + p[k2] * node[k2];
  const double q = 1 - p[zero] * p[zero];
  g[zero] = -0.5 * p[zero] * b * c;
  g[k1] = 0.25 * q * node[k1] * c;
  g[k2] = 0.25 * q * b * node[k2];
  return g;
}

}  // namespace

QuadraticJacobian quadratic_hex_jacobian(const std::array<core::Vec3, 20>& nodes) {
  static const std::array<Eigen::Vector3d, 20> kRef = reference_nodes();
  const double gauss[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  QuadraticJacobian out;
  out.min_det = std::numeric_limits<double>::infinity();
  out.max_det = -out.min_det;
  for (double x : gauss)
    for (double y : gauss)
      for (double z : gauss) {
        const Eigen::Vector3d p(x, y, z);
        Eigen::Matrix3d j = Eigen::Matrix3d::Zero();  // j(r, k) = d x_r / d p_k
        for (int i = 0; i < 20; ++i) j += nodes[i] * shape_gradient(kRef[i], p).transpose();
        const double det = j.determinant();
        out.min_det = std::min(out.min_det, det);
        out.max_det = std::max(out.max_det, det);
      }
  return out;
}

}  // namespace vorohex::quality
