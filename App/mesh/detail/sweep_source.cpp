#include "mesh/detail/sweep_source.h"

#include <algorithm>
#include <utility>

#include "mesh/detail/quad_quality.h"

namespace vorohex::mesh::detail {

using core::Vec3;

bool source_from_quads(const core::MeshDomain& solid, core::FaceId source,
                       const std::vector<std::vector<Vec3>>& loops,
                       const std::vector<std::array<Vec3, 4>>& quads, double tol,
                       QuadFaceMesh& out) {
  if (quads.empty()) return false;
  QuadFaceMesh m;
  for (const auto& loop : loops) m.points.insert(m.points.end(), loop.begin(), loop.end());
  m.num_boundary = m.points.size();
  std::vector<char> used(m.num_boundary, 0);
  auto node = [&](const Vec3& x) {
    for (std::size_t j = 0; j < m.points.size(); ++j)
      if ((m.points[j] - x).norm() <= tol) {
        if (j < m.num_boundary) used[j] = 1;
        return int(j);
      }
    m.points.push_back(x);
    return int(m.points.size() - 1);
  };
  for (const auto& q : quads) {
    std::array<int, 4> k = {node(q[0]), node(q[1]), node(q[2]), node(q[3])};
    const Vec3 c = 0.25 * (q[0] + q[1] + q[2] + q[3]);
    if ((q[2] - q[0]).cross(q[3] - q[1]).dot(solid.face_normal(source, c)) < 0)
      std::swap(k[1], k[3]);
    m.quads.push_back(k);
  }
  if (std::find(used.begin(), used.end(), 0) != used.end()) return false;
  std::size_t boundary_sides = 0;
  for (const auto& q : m.quads)
    for (int c = 0; c < 4; ++c)
      boundary_sides +=
          std::size_t(q[c]) < m.num_boundary && std::size_t(q[(c + 1) % 4]) < m.num_boundary;
  if (boundary_sides < m.num_boundary) return false;
  m.ok = true;
  measure_quads(solid, source, m);
  out = std::move(m);
  return true;
}

}  // namespace vorohex::mesh::detail
