#include "quality/linear_gauss_jacobian.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace vorohex::quality {

double linear_hex_gauss_min_det(const std::array<core::Vec3, 8>& corners) {
  static const int kSign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                  {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  const double g = 1.0 / std::sqrt(3.0);
  double out = std::numeric_limits<double>::infinity();
  for (int q = 0; q < 8; ++q) {
    const double p[3] = {kSign[q][0] * g, kSign[q][1] * g, kSign[q][2] * g};
    Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
    for (int i = 0; i < 8; ++i) {
      const double a[3] = {1 + p[0] * kSign[i][0], 1 + p[1] * kSign[i][1], 1 + p[2] * kSign[i][2]};
      const Eigen::Vector3d grad(kSign[i][0] * a[1] * a[2] / 8, a[0] * kSign[i][1] * a[2] / 8,
                                 a[0] * a[1] * kSign[i][2] / 8);
      j += corners[i] * grad.transpose();
    }
    out = std::min(out, j.determinant());
  }
  return out;
}

}  // namespace vorohex::quality
