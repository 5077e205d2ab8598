#include "mesh/detail/tet_to_hex.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <map>

namespace vorohex::mesh::detail {

using core::NodeId;
using core::Vec3;

void add_hex_positive_at_corner0(core::HexMesh& m, core::HexNodes h, std::int32_t sub_volume) {
  const Vec3 o = m.point(NodeId(h[0]));
  const Vec3 a = m.point(NodeId(h[1])) - o, b = m.point(NodeId(h[3])) - o,
             c = m.point(NodeId(h[4])) - o;
  if (a.dot(b.cross(c)) < 0) {
    std::swap(h[1], h[3]);
    std::swap(h[5], h[7]);
  }
  m.add_hex(h, sub_volume);
}

TetSplitNodes split_tetrahedra(core::HexMesh& m, const std::vector<std::array<int, 4>>& tets) {
  TetSplitNodes out;
  out.first_new = m.num_nodes();
  std::map<std::array<int, 2>, int> mids;
  std::map<std::array<int, 3>, int> centroids;
  auto pt = [&](int n) { return m.point(NodeId(n)); };
  auto add = [&](const Vec3& p, std::array<int, 3> origin) {
    out.origin.push_back(origin);
    return static_cast<int>(m.add_node(p).value());
  };
  auto mid = [&](int x, int y) {
    const std::array<int, 2> k{std::min(x, y), std::max(x, y)};
    auto it = mids.find(k);
    if (it != mids.end()) return it->second;
    return mids[k] = add((pt(x) + pt(y)) / 2, {k[0], k[1], -1});
  };
  auto centroid = [&](int x, int y, int z) {
    std::array<int, 3> k{x, y, z};
    std::sort(k.begin(), k.end());
    auto it = centroids.find(k);
    if (it != centroids.end()) return it->second;
    return centroids[k] = add((pt(x) + pt(y) + pt(z)) / 3, k);
  };
  for (const std::array<int, 4>& t : tets) {
    const int tc = add((pt(t[0]) + pt(t[1]) + pt(t[2]) + pt(t[3])) / 4, {-1, -1, -1});
    for (int i = 0; i < 4; ++i) {
      const int c = t[i], j = t[(i + 1) % 4], k = t[(i + 2) % 4], l = t[(i + 3) % 4];
      add_hex_positive_at_corner0(m, {c, mid(c, j), centroid(c, j, k), mid(c, k), mid(c, l),
                                      centroid(c, j, l), tc, centroid(c, k, l)});
    }
  }
  return out;
}

}  // namespace vorohex::mesh::detail
