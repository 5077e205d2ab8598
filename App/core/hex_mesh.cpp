#include "core/hex_mesh.h"

#include <algorithm>
#include <array>
#include <limits>

namespace vorohex::core {

// Outward faces of a positively oriented VTK hexahedron.
const std::array<std::array<int, 4>, 6> kHexFaces = {{
    {0, 3, 2, 1},  // bottom (z = 0 in the reference cube)
    {4, 5, 6, 7},  // top
    {0, 1, 5, 4},  // y = 0
    {2, 3, 7, 6},  // y = 1
    {0, 4, 7, 3},  // x = 0
    {1, 2, 6, 5},  // x = 1
}};

const std::array<std::array<int, 2>, 12> kHexEdges = {{
    {0, 1},
    {1, 2},
    {2, 3},
    {3, 0},
    {4, 5},
    {5, 6},
    {6, 7},
    {7, 4},
    {0, 4},
    {1, 5},
    {2, 6},
    {3, 7},
}};

void HexMesh::reserve(std::size_t nodes, std::size_t hexes) {
  points_.reserve(nodes);
  classes_.reserve(nodes);
  hexes_.reserve(hexes);
  sub_volumes_.reserve(hexes);
}

NodeId HexMesh::add_node(const Vec3& p, NodeClass c) {
  points_.push_back(p);
  classes_.push_back(c);
  return NodeId(static_cast<std::int32_t>(points_.size() - 1));
}

HexId HexMesh::add_hex(const HexNodes& nodes, std::int32_t sub_volume) {
  hexes_.push_back(nodes);
  sub_volumes_.push_back(sub_volume);
  return HexId(static_cast<std::int32_t>(hexes_.size() - 1));
}

std::array<Vec3, 8> HexMesh::corners(HexId h) const {
  std::array<Vec3, 8> c;
  const HexNodes& n = hexes_[h.value()];
  for (int i = 0; i < 8; ++i) c[i] = points_[n[i]];
  return c;
}

std::size_t HexMesh::append(const HexMesh& other) {
  const std::size_t offset = points_.size();
  points_.insert(points_.end(), other.points_.begin(), other.points_.end());
  classes_.insert(classes_.end(), other.classes_.begin(), other.classes_.end());
  hexes_.reserve(hexes_.size() + other.hexes_.size());
  for (HexNodes h : other.hexes_) {
    for (auto& n : h) n += static_cast<std::int32_t>(offset);
    hexes_.push_back(h);
  }
  sub_volumes_.insert(sub_volumes_.end(), other.sub_volumes_.begin(), other.sub_volumes_.end());
  if (other.order() == 2) {
    mid_edges_.reserve(hexes_.size());
    for (MidEdgeNodes m : other.mid_edges_) {
      for (auto& n : m) n += static_cast<std::int32_t>(offset);
      mid_edges_.push_back(m);
    }
  }
  return offset;
}

BoundingBox HexMesh::bounding_box() const {
  BoundingBox b;
  if (points_.empty()) return b;
  const double inf = std::numeric_limits<double>::infinity();
  b.min = Vec3(inf, inf, inf);
  b.max = -b.min;
  for (const Vec3& p : points_) {
    b.min = b.min.cwiseMin(p);
    b.max = b.max.cwiseMax(p);
  }
  return b;
}

std::vector<BoundaryFace> boundary_faces(const HexMesh& mesh) {
  // Faces bucketed by their smallest node (CSR), then compared within a bucket: linear
  // time and 4 bytes per face, where a hash map of all faces took most of the time.
  const auto& hexes = mesh.hexes();
  const std::size_t n_faces = hexes.size() * 6;
  auto key = [&](std::size_t face) {
    std::array<std::int32_t, 4> k;
    const auto& quad = kHexFaces[face % 6];
    for (int i = 0; i < 4; ++i) k[i] = hexes[face / 6][quad[i]];
    std::sort(k.begin(), k.end());
    return k;
  };
  std::vector<std::uint32_t> start(mesh.num_nodes() + 1, 0);
  for (std::size_t f = 0; f < n_faces; ++f) {
    const auto k = key(f);
    if (k[0] >= 0 && static_cast<std::size_t>(k[0]) < mesh.num_nodes()) ++start[k[0] + 1];
  }
  for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  std::vector<std::uint32_t> bucket(start.back());
  for (std::size_t f = 0; f < n_faces; ++f) {
    const auto k = key(f);
    if (k[0] >= 0 && static_cast<std::size_t>(k[0]) < mesh.num_nodes())
      bucket[fill[k[0]]++] = static_cast<std::uint32_t>(f);
  }
  std::vector<char> shared(n_faces, 0);
  for (std::size_t node = 0; node + 1 < start.size(); ++node)
    for (std::uint32_t a = start[node]; a < start[node + 1]; ++a) {
      const auto ka = key(bucket[a]);
      for (std::uint32_t b = a + 1; b < start[node + 1]; ++b)
        if (key(bucket[b]) == ka) shared[bucket[a]] = shared[bucket[b]] = 1;
    }
  std::vector<BoundaryFace> out;
  for (std::size_t f = 0; f < n_faces; ++f)
    if (!shared[f])
      out.push_back({static_cast<std::int32_t>(f / 6), static_cast<std::int8_t>(f % 6)});
  return out;
}

std::vector<char> boundary_nodes(const HexMesh& mesh) {
  std::vector<char> out(mesh.num_nodes(), 0);
  for (const BoundaryFace& b : boundary_faces(mesh))
    for (int corner : kHexFaces[std::size_t(b.face)])
      out[std::size_t(mesh.hexes()[std::size_t(b.hex)][corner])] = 1;
  return out;
}

}  // namespace vorohex::core
