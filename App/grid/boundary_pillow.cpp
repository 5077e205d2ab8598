#include "grid/boundary_pillow.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vorohex::grid {

BoundaryPillowResult pillow_boundary(core::HexMesh& mesh, double shrink) {
  if (!(shrink > 0 && shrink < 1))
    throw std::invalid_argument("pillow_boundary: shrink must be in (0, 1)");
  BoundaryPillowResult r;
  const std::vector<core::BoundaryFace> faces = core::boundary_faces(mesh);
  if (faces.empty()) return r;
  const std::vector<char> on_boundary = core::boundary_nodes(mesh);
  const std::size_t n = mesh.num_nodes();

  // Per boundary node: the ends of its interior edges (nodes not on the boundary, each once)
  // and the sum of its hexahedra's centroids.
  std::vector<int> hexes_at(n, 0);
  std::vector<core::Vec3> centroid_sum(n, core::Vec3::Zero());
  std::vector<std::vector<std::int32_t>> inward(n);
  for (std::size_t h = 0; h < mesh.num_hexes(); ++h) {
    const core::HexNodes& hx = mesh.hex(core::HexId(std::int32_t(h)));
    core::Vec3 c = core::Vec3::Zero();
    for (std::int32_t v : hx) c += mesh.point(core::NodeId(v));
    c /= 8.0;
    for (std::int32_t v : hx)
      if (on_boundary[v]) centroid_sum[v] += c, ++hexes_at[v];
    for (const auto& e : core::kHexEdges) {
      for (int s = 0; s < 2; ++s) {
        const std::int32_t a = hx[e[s]], b = hx[e[1 - s]];
        if (!on_boundary[a] || on_boundary[b]) continue;
        std::vector<std::int32_t>& ends = inward[a];
        if (std::find(ends.begin(), ends.end(), b) == ends.end()) ends.push_back(b);
      }
    }
  }

  // The twins: numbered after the existing nodes, in node order.
  std::vector<std::int32_t> twin(n, -1);
  for (std::size_t v = 0; v < n; ++v) {
    if (!on_boundary[v]) continue;
    const core::Vec3 p = mesh.point(core::NodeId(std::int32_t(v)));
    core::Vec3 q;
    if (inward[v].size() == 1)
      q = p + shrink * (mesh.point(core::NodeId(inward[v][0])) - p);
    else
      q = p + std::min(1.0, 2 * shrink) * (centroid_sum[v] / double(hexes_at[v]) - p);
    twin[v] = mesh.add_node(q).value();
    ++r.nodes_added;
  }

  // Rebuild: the old hexahedra on the twins, then one hexahedron per boundary quad.
  core::HexMesh out;
  out.reserve(mesh.num_nodes(), mesh.num_hexes() + faces.size());
  for (std::size_t v = 0; v < mesh.num_nodes(); ++v) {
    const core::NodeId id{std::int32_t(v)};
    out.add_node(mesh.point(id), mesh.node_class(id));
  }
  for (std::size_t h = 0; h < mesh.num_hexes(); ++h) {
    const core::HexId id{std::int32_t(h)};
    core::HexNodes hx = mesh.hex(id);
    for (std::int32_t& v : hx)
      if (twin[v] >= 0) v = twin[v];
    out.add_hex(hx, mesh.sub_volume(id));
  }
  for (const core::BoundaryFace& f : faces) {
    const core::HexId id{f.hex};
    const core::HexNodes& hx = mesh.hex(id);
    const auto& c = core::kHexFaces[f.face];
    core::HexNodes layer;
    for (int i = 0; i < 4; ++i) layer[i] = twin[hx[c[i]]], layer[i + 4] = hx[c[i]];
    out.add_hex(layer, mesh.sub_volume(id));
    ++r.hexes_added;
  }
  mesh = std::move(out);
  return r;
}

std::size_t flat_doublets(const core::HexMesh& mesh, double max_turn_degrees) {
  const double min_cos = std::cos(max_turn_degrees * M_PI / 180);
  const std::vector<core::BoundaryFace> faces = core::boundary_faces(mesh);
  std::size_t count = 0;
  // boundary_faces lists a hexahedron's quads together (hexahedron order).
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i;
    while (j < faces.size() && faces[j].hex == faces[i].hex) ++j;
    const core::HexNodes& hx = mesh.hex(core::HexId(faces[i].hex));
    auto normal = [&](int face) {
      const auto& c = core::kHexFaces[face];
      const core::Vec3 d1 = mesh.point(core::NodeId(hx[c[2]])) - mesh.point(core::NodeId(hx[c[0]]));
      const core::Vec3 d2 = mesh.point(core::NodeId(hx[c[3]])) - mesh.point(core::NodeId(hx[c[1]]));
      const core::Vec3 n = d1.cross(d2);
      return n.norm() > 0 ? core::Vec3(n.normalized()) : n;
    };
    bool flat = false;
    for (std::size_t a = i; a < j && !flat; ++a)
      for (std::size_t b = a + 1; b < j && !flat; ++b) {
        const auto &fa = core::kHexFaces[faces[a].face], &fb = core::kHexFaces[faces[b].face];
        int common = 0;  // faces across an edge share two nodes; opposite faces none
        for (int x : fa)
          for (int y : fb) common += x == y;
        flat = common == 2 && normal(faces[a].face).dot(normal(faces[b].face)) > min_cos;
      }
    count += flat;
    i = j;
  }
  return count;
}

}  // namespace vorohex::grid
