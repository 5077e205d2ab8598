#include "mesh/detail/boundary_labels.h"

#include <algorithm>

namespace vorohex::mesh::detail {

std::array<int, 3> facet_of(const std::array<int, 4>& t, int skip) {
  std::array<int, 3> k;
  for (int j = 0, n = 0; j < 4; ++j)
    if (j != skip) k[n++] = t[j];
  std::sort(k.begin(), k.end());
  return k;
}

BoundaryLabels boundary_labels(const std::vector<std::array<int, 4>>& tets,
                               const std::vector<core::Vec3>& points,
                               const std::vector<std::array<int, 3>>& surface_facets,
                               const std::vector<int>& surface_patch, const occ::Solid& solid) {
  std::map<std::array<int, 3>, int> uses;
  for (const auto& t : tets)
    for (int skip = 0; skip < 4; ++skip) ++uses[facet_of(t, skip)];
  BoundaryLabels out;
  out.node_face.assign(points.size(), 0);
  auto label = [&](const std::array<int, 3>& k, int face) {
    out.facet_face[k] = face;
    out.edge_face[{k[0], k[1]}] = out.edge_face[{k[1], k[2]}] = out.edge_face[{k[0], k[2]}] = face;
    for (int v : k) out.node_face[v] = face;
  };
  for (std::size_t i = 0; i < surface_facets.size() && i < surface_patch.size(); ++i) {
    const int face = surface_patch[i];
    if (face < 1 || face > solid.num_faces()) continue;
    const auto it = uses.find(surface_facets[i]);
    if (it != uses.end() && it->second == 1) label(surface_facets[i], face);
  }
  for (const auto& [k, n] : uses)
    if (n == 1 && !out.facet_face.count(k))
      label(k, solid.nearest_face((points[k[0]] + points[k[1]] + points[k[2]]) / 3.0).value());
  return out;
}

}  // namespace vorohex::mesh::detail
