// A 2-D chart of one face, for meshers that work in the plane: the face's own plane for
// planar faces, the surface's (u, v) scaled by its metric at the face centre otherwise.
// The chart may be mirrored with respect to the face's outward normal; callers check the
// orientation of the boundary loops they map.
#pragma once

#include <Eigen/Core>
#include <memory>

#include "occ/solid.h"

namespace vorohex::occ {

class FaceChart : public core::SurfaceChart {
 public:
  // Throws std::runtime_error when the surface cannot be evaluated.
  FaceChart(const Solid& solid, FaceId face);
  FaceChart(FaceChart&&) noexcept;
  ~FaceChart() override;

  Eigen::Vector2d to_chart(const Vec3& p) const override;    // p on or near the face
  Vec3 to_surface(const Eigen::Vector2d& q) const override;  // the surface point of q
  bool planar() const override { return planar_; }

 private:
  struct Surface;  // OCCT side (curved faces only)
  bool planar_ = false;
  Vec3 origin_, e1_, e2_;   // planar faces: p = origin + x e1 + y e2
  double su_ = 1, sv_ = 1;  // curved faces: chart = (u su, v sv)
  double umin_ = 0, umax_ = 0, vmin_ = 0, vmax_ = 0;
  std::unique_ptr<Surface> surface_;
};

}  // namespace vorohex::occ
