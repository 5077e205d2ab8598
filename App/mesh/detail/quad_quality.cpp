#include "mesh/detail/quad_quality.h"

#include <Eigen/Geometry>
#include <algorithm>

namespace vorohex::mesh::detail {

using core::Vec3;

void measure_quads(const core::MeshDomain& solid, core::FaceId face, QuadFaceMesh& m) {
  double orientation = 0;
  for (const auto& q : m.quads) {
    const Vec3 a = m.points[q[1]] - m.points[q[0]], b = m.points[q[3]] - m.points[q[0]];
    orientation += a.cross(b).dot(solid.face_normal(face, m.points[q[0]]));
  }
  const double sign = orientation < 0 ? -1.0 : 1.0;
  double sum = 0;
  m.min_quality = 1;
  for (const auto& q : m.quads) {
    Vec3 c = Vec3::Zero();
    for (int v : q) c += m.points[v] / 4;
    const Vec3 n = sign * solid.face_normal(face, c);
    double worst = 1;
    for (int a = 0; a < 4; ++a) {
      const Vec3 e1 = m.points[q[(a + 1) % 4]] - m.points[q[a]];
      const Vec3 e2 = m.points[q[(a + 3) % 4]] - m.points[q[a]];
      const double l = e1.norm() * e2.norm();
      worst = std::min(worst, l > 0 ? e1.cross(e2).dot(n) / l : -1.0);
    }
    m.min_quality = std::min(m.min_quality, worst);
    sum += worst;
  }
  m.mean_quality = m.quads.empty() ? 0 : sum / double(m.quads.size());
}

}  // namespace vorohex::mesh::detail
