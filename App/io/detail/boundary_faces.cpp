#include "io/detail/boundary_faces.h"

#include <algorithm>
#include <array>

namespace vorohex::io::detail {
std::vector<BoundaryFace> boundary_faces(const core::HexMesh& mesh) {
  // Faces bucketed by their smallest node (CSR), then compared within a bucket: linear
  // time and 4 bytes per face, where a hash map of all faces took most of the time.
  const auto& hexes = mesh.hexes();
  const std::size_t n_faces = hexes.size() * 6;
  auto key = [&](std::size_t face) {
    std::array<std::int32_t, 4> k;
    const auto& quad = core::kHexFaces[face % 6];
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

int abaqus_face_number(int hex_face) {
  // kHexFaces: bottom {0,3,2,1} = S1, top {4,5,6,7} = S2, y0 {0,1,5,4} = S3,
  // y1 {2,3,7,6} = S5, x0 {0,4,7,3} = S6, x1 {1,2,6,5} = S4.
  static const int kNumber[6] = {1, 2, 3, 5, 6, 4};
  return kNumber[hex_face];
}

}  // namespace vorohex::io::detail
