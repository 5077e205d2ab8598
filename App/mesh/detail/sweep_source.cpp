#include "mesh/detail/sweep_source.h"

#include <algorithm>
#include <limits>
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

bool onto_target_quads(std::vector<core::Vec3>& P, std::size_t base, std::size_t m, std::size_t nb,
                       const std::vector<std::array<core::Vec3, 4>>& quads, double size) {
  using core::Vec3;
  const double tol = 1e-6 * size;
  std::vector<Vec3> inner;  // distinct corners that are not boundary nodes
  for (const auto& q : quads)
    for (const Vec3& c : q) {
      bool known = false;
      for (std::size_t j = 0; j < nb && !known; ++j) known = (P[base + j] - c).norm() <= tol;
      for (std::size_t i = 0; i < inner.size() && !known; ++i) known = (inner[i] - c).norm() <= tol;
      if (!known) inner.push_back(c);
    }
  if (inner.size() != m - nb) return false;
  std::vector<char> used(inner.size(), 0);
  for (std::size_t j = nb; j < m; ++j) {
    const Vec3 p = P[base + j];
    std::size_t best = inner.size();
    for (std::size_t i = 0; i < inner.size(); ++i)
      if (!used[i] && (best == inner.size() || (inner[i] - p).norm() < (inner[best] - p).norm()))
        best = i;
    double room = std::numeric_limits<double>::infinity();  // to its nearest other node
    for (std::size_t i = 0; i < m; ++i)
      if (i != j) room = std::min(room, (P[base + i] - p).norm());
    if (best == inner.size() || (inner[best] - p).norm() > 0.5 * room) return false;
    used[best] = 1;
    P[base + j] = inner[best];
  }
  return true;
}

}  // namespace vorohex::mesh::detail
