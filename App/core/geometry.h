// Basic geometric value types shared by every stage.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products and frames on Vec3 everywhere
#include <array>

namespace vorohex::core {

using Vec3 = Eigen::Vector3d;

struct BoundingBox {
  Vec3 min{0, 0, 0};
  Vec3 max{0, 0, 0};
  double diagonal() const { return (max - min).norm(); }
};

}  // namespace vorohex::core
