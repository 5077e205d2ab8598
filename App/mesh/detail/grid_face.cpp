#include "mesh/detail/grid_face.h"

#include <algorithm>

#include "mesh/detail/quad_quality.h"

namespace vorohex::mesh::detail {

using core::FaceId;
using core::Vec3;
using occ::Solid;

std::vector<Vec3> grid_inner_nodes(const Solid& solid, FaceId face, const std::vector<Vec3>& loop,
                                   int n0, int n1) {
  auto at = [&](int i, int j) -> const Vec3& {
    if (j == 0) return loop[i];
    if (i == n0) return loop[n0 + j];
    if (j == n1) return loop[n0 + n1 + (n0 - i)];
    return loop[(2 * n0 + n1 + (n1 - j)) % loop.size()];
  };
  const bool curved = !solid.face_is_planar(face);
  std::vector<Vec3> inner;
  inner.reserve(std::size_t(std::max(0, n0 - 1)) * std::max(0, n1 - 1));
  for (int j = 1; j < n1; ++j) {
    const double v = double(j) / n1;
    for (int i = 1; i < n0; ++i) {
      const double u = double(i) / n0;
      const Vec3 q = (1 - u) * at(0, j) + u * at(n0, j) + (1 - v) * at(i, 0) + v * at(i, n1) -
                     ((1 - u) * (1 - v) * at(0, 0) + u * (1 - v) * at(n0, 0) +
                      (1 - u) * v * at(0, n1) + u * v * at(n0, n1));
      inner.push_back(curved ? solid.project_to_face(face, q) : q);
    }
  }
  return inner;
}

// The source as a transfinite grid in QuadFaceMesh form (boundary loop, then inner nodes;
// quads counter-clockwise seen from outside, as the loop runs).
QuadFaceMesh grid_face(const Solid& solid, FaceId face, const std::vector<Vec3>& loop, int n0,
                       int n1) {
  QuadFaceMesh m;
  m.points = loop;
  m.num_boundary = loop.size();
  const std::vector<Vec3> inner = grid_inner_nodes(solid, face, loop, n0, n1);
  m.points.insert(m.points.end(), inner.begin(), inner.end());
  auto index = [&](int i, int j) -> int {
    if (j == 0) return i;
    if (i == n0) return n0 + j;
    if (j == n1) return n0 + n1 + (n0 - i);
    if (i == 0) return (2 * n0 + n1 + (n1 - j)) % int(loop.size());
    return int(loop.size()) + (j - 1) * (n0 - 1) + (i - 1);
  };
  for (int j = 0; j < n1; ++j)
    for (int i = 0; i < n0; ++i)
      m.quads.push_back({index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)});
  measure_quads(solid, face, m);
  m.ok = true;
  return m;
}

}  // namespace vorohex::mesh::detail
