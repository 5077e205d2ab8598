#include "smooth/detail/topology.h"

#include <algorithm>
#include <array>
#include <utility>

namespace vorohex::smooth::detail {
namespace {

using core::HexMesh;
using core::NodeClass;

// Boundary quads are faces of exactly one hex; only faces whose four nodes are all
// classified on the boundary can be one, which keeps the sort small for large meshes.
std::vector<std::array<std::int32_t, 4>> boundary_quads(const HexMesh& mesh) {
  const auto& classes = mesh.node_classes();
  struct Face {
    std::array<std::int32_t, 4> key;   // sorted node ids
    std::array<std::int32_t, 4> quad;  // in hex order
  };
  std::vector<Face> faces;
  for (const auto& hex : mesh.hexes())
    for (const auto& f : core::kHexFaces) {
      Face face;
      bool boundary = true;
      for (int i = 0; i < 4; ++i) {
        face.quad[i] = hex[f[i]];
        boundary = boundary && !classes[face.quad[i]].is_interior();
      }
      if (!boundary) continue;
      face.key = face.quad;
      std::sort(face.key.begin(), face.key.end());
      faces.push_back(face);
    }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.key < b.key; });
  std::vector<std::array<std::int32_t, 4>> quads;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j - i == 1) quads.push_back(faces[i].quad);
    i = j;
  }
  return quads;
}

}  // namespace

SmoothTopology build_topology(const HexMesh& mesh) {
  SmoothTopology t;
  const std::size_t nn = mesh.num_nodes();
  const auto& hexes = mesh.hexes();
  const auto& classes = mesh.node_classes();

  // node -> (hex, corner)
  t.node_hexes.offsets.assign(nn + 1, 0);
  for (const auto& hex : hexes)
    for (std::int32_t n : hex) ++t.node_hexes.offsets[n + 1];
  for (std::size_t i = 0; i < nn; ++i) t.node_hexes.offsets[i + 1] += t.node_hexes.offsets[i];
  t.node_hexes.items.resize(t.node_hexes.offsets[nn]);
  {
    std::vector<std::int64_t> fill(t.node_hexes.offsets.begin(), t.node_hexes.offsets.end() - 1);
    for (std::size_t h = 0; h < hexes.size(); ++h)
      for (int c = 0; c < 8; ++c)
        t.node_hexes.items[fill[hexes[h][c]]++] = static_cast<std::int32_t>(h * 8 + c);
  }

  // Boundary-quad edges, both directions, sorted by source node.
  const auto quads = boundary_quads(mesh);
  t.boundary_quads = quads.size();
  std::vector<std::pair<std::int32_t, std::int32_t>> bedges;
  bedges.reserve(quads.size() * 8);
  for (const auto& q : quads)
    for (int i = 0; i < 4; ++i) {
      bedges.emplace_back(q[i], q[(i + 1) % 4]);
      bedges.emplace_back(q[(i + 1) % 4], q[i]);
    }
  std::sort(bedges.begin(), bedges.end());
  bedges.erase(std::unique(bedges.begin(), bedges.end()), bedges.end());

  t.neighbours.offsets.assign(nn + 1, 0);
  t.neighbours.items.reserve(nn * 6);
  std::vector<std::int32_t> local;
  std::size_t b = 0;  // cursor into bedges
  for (std::size_t n = 0; n < nn; ++n) {
    local.clear();
    const NodeClass c = classes[n];
    const std::size_t b0 = b;
    while (b < bedges.size() && bedges[b].first == static_cast<std::int32_t>(n)) ++b;
    if (c.is_interior()) {
      for (std::int64_t k = t.node_hexes.begin(n); k < t.node_hexes.end(n); ++k) {
        const std::int32_t item = t.node_hexes.items[k];
        for (int j = 0; j < 3; ++j)
          local.push_back(hexes[item / 8][kCornerNeighbours[item % 8][j]]);
      }
      std::sort(local.begin(), local.end());
      local.erase(std::unique(local.begin(), local.end()), local.end());
    } else if (c.dim == 2) {
      for (std::size_t k = b0; k < b; ++k) local.push_back(bedges[k].second);
    } else if (c.dim == 1) {
      for (std::size_t k = b0; k < b; ++k) {
        const NodeClass o = classes[bedges[k].second];
        if (o.dim == 0 || (o.dim == 1 && o.id == c.id)) local.push_back(bedges[k].second);
      }
    }
    t.neighbours.items.insert(t.neighbours.items.end(), local.begin(), local.end());
    t.neighbours.offsets[n + 1] = static_cast<std::int64_t>(t.neighbours.items.size());
  }
  return t;
}

}  // namespace vorohex::smooth::detail
