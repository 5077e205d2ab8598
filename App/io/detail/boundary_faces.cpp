#include "io/detail/boundary_faces.h"

#include <algorithm>
#include <unordered_map>

namespace vorohex::io::detail {
namespace {

struct QuadKey {
  std::array<std::int32_t, 4> n;
  bool operator==(const QuadKey& o) const { return n == o.n; }
};
struct QuadHash {
  std::size_t operator()(const QuadKey& k) const {
    std::size_t h = 1469598103934665603ull;
    for (std::int32_t v : k.n) h = (h ^ static_cast<std::uint32_t>(v)) * 1099511628211ull;
    return h;
  }
};

}  // namespace

std::vector<BoundaryFace> boundary_faces(const core::HexMesh& mesh) {
  const auto& hexes = mesh.hexes();
  std::unordered_map<QuadKey, int, QuadHash> count;
  count.reserve(hexes.size() * 4);
  auto key = [&](std::size_t h, int f) {
    QuadKey k;
    for (int i = 0; i < 4; ++i) k.n[i] = hexes[h][core::kHexFaces[f][i]];
    std::sort(k.n.begin(), k.n.end());
    return k;
  };
  for (std::size_t h = 0; h < hexes.size(); ++h)
    for (int f = 0; f < 6; ++f) ++count[key(h, f)];
  std::vector<BoundaryFace> out;
  for (std::size_t h = 0; h < hexes.size(); ++h)
    for (int f = 0; f < 6; ++f)
      if (count[key(h, f)] == 1)
        out.push_back({static_cast<std::int32_t>(h), static_cast<std::int8_t>(f)});
  return out;
}

int abaqus_face_number(int hex_face) {
  // kHexFaces: bottom {0,3,2,1} = S1, top {4,5,6,7} = S2, y0 {0,1,5,4} = S3,
  // y1 {2,3,7,6} = S5, x0 {0,4,7,3} = S6, x1 {1,2,6,5} = S4.
  static const int kNumber[6] = {1, 2, 3, 5, 6, 4};
  return kNumber[hex_face];
}

}  // namespace vorohex::io::detail
