#include "grid/detail/pillow.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace vorohex::grid::detail {
namespace {
// VTK corner b of cell (i, j, k): its offsets along the three axes.
constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                               {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
}  // namespace

QuadKey quad_key(const std::array<std::int32_t, 8>& hex, int face) {
  const auto& c = core::kHexFaces[face];
  QuadKey k = {hex[c[0]], hex[c[1]], hex[c[2]], hex[c[3]]};
  std::sort(k.begin(), k.end());
  return k;
}

PillowMesh pillow_mesh(const GridFrame& frame, const CoreCells& core,
                       const core::MeshDomain& solid) {
  const int n0 = frame.nodes(0), n1 = frame.nodes(1);
  std::vector<core::Vec3> points;
  std::unordered_map<std::size_t, std::int32_t> node_of;  // grid node -> point
  auto point = [&](int i, int j, int k) {
    const std::size_t g = std::size_t(i) + std::size_t(n0) * (std::size_t(j) + std::size_t(n1) * k);
    auto [it, fresh] = node_of.try_emplace(g, std::int32_t(points.size()));
    if (fresh) points.push_back(frame.point(i, j, k));
    return it->second;
  };
  std::vector<std::array<std::int32_t, 8>> hexes;
  for (int k = 0; k < core.cells[2]; ++k)
    for (int j = 0; j < core.cells[1]; ++j)
      for (int i = 0; i < core.cells[0]; ++i) {
        if (!core.at(i, j, k)) continue;
        std::array<std::int32_t, 8> h;
        for (int b = 0; b < 8; ++b)
          h[b] = point(i + kCorner[b][0], j + kCorner[b][1], k + kCorner[b][2]);
        hexes.push_back(h);
      }
  return pillow_mesh(points, hexes, frame.axes, solid);
}

PillowMesh pillow_mesh(const std::vector<core::Vec3>& points,
                       const std::vector<std::array<std::int32_t, 8>>& hexes,
                       const std::array<core::Vec3, 3>& axes, const core::MeshDomain& solid) {
  PillowMesh out;
  std::unordered_map<std::int32_t, std::int32_t> node_of;  // point -> mesh node
  auto mesh_node = [&](std::int32_t p) {
    auto [it, fresh] = node_of.try_emplace(p, 0);
    if (fresh) it->second = out.mesh.add_node(points[p]).value();
    return it->second;
  };
  // Faces of the core by their sorted points: a face used once is on the core's boundary.
  std::unordered_map<QuadKey, int, QuadKeyHash> uses;
  for (const auto& h : hexes)
    for (int f = 0; f < 6; ++f) ++uses[quad_key(h, f)];
  struct Quad {
    std::array<std::int32_t, 4> nodes;
  };
  std::vector<Quad> quads;
  for (const auto& hp : hexes) {
    core::HexNodes h;
    for (int b = 0; b < 8; ++b) h[b] = mesh_node(hp[b]);
    out.mesh.add_hex(h, 1);
    ++out.core_hexes;
    for (int fi = 0; fi < 6; ++fi)
      if (uses[quad_key(hp, fi)] == 1) {
        const auto& f = core::kHexFaces[fi];
        quads.push_back({{h[f[0]], h[f[1]], h[f[2]], h[f[3]]}});
      }
  }
  // Outer nodes. A node's outward direction n is the mean of the normals of its boundary
  // quads; its outer node is the closest boundary point to p + 2 d n (d: its distance to
  // the boundary), which for a core corner or edge opposite a model vertex or edge is that
  // vertex or a point of that edge (a plain closest point would be on one of the faces),
  // and on a flat stretch the foot of the normal. The plain closest point is kept when it
  // lies more nearly along n (towards a concave edge) or the shifted one is far off (the
  // shifted point crossed a thin wall).
  std::unordered_map<std::int32_t, core::Vec3> normal_of;
  std::unordered_map<std::int32_t, int> directions_of;
  for (const Quad& q : quads) {
    const core::Vec3 a = out.mesh.point(core::NodeId(q.nodes[0])),
                     b = out.mesh.point(core::NodeId(q.nodes[1])),
                     c = out.mesh.point(core::NodeId(q.nodes[2]));
    const core::Vec3 n = (b - a).cross(c - b).normalized();
    // Each of the six grid directions counts once (a core corner has three, a concave
    // corner's many quads on one side would otherwise outweigh the others).
    int dir = 0;
    for (int a = 0; a < 3; ++a)
      if (std::abs(n.dot(axes[a])) > 0.5) dir = 1 << (2 * a + (n.dot(axes[a]) > 0));
    for (std::int32_t v : q.nodes) {
      auto [it, fresh] = normal_of.try_emplace(v, core::Vec3::Zero());
      int& seen = directions_of[v];
      if (!(seen & dir)) it->second += n, seen |= dir;
    }
  }
  std::vector<std::int32_t> inner;
  for (auto& [n, normal] : normal_of) inner.push_back(n);
  std::sort(inner.begin(), inner.end());  // deterministic numbering
  std::unordered_map<std::int32_t, std::int32_t> outer_of;
  for (std::int32_t n : inner) {
    const core::Vec3 p = out.mesh.point(core::NodeId(n));
    core::FaceId f = solid.nearest_face(p);
    core::Vec3 q = f.value() > 0 ? solid.project_to_face(f, p) : p;
    const double d = (q - p).norm();
    const core::Vec3 dir = normal_of[n].normalized();
    if (d > 0 && dir.allFinite()) {
      const core::Vec3 shifted = p + dir * (2 * d);
      const core::FaceId f2 = solid.nearest_face(shifted);
      if (f2.value() > 0) {
        const core::Vec3 q2 = solid.project_to_face(f2, shifted);
        // The candidate more nearly along n (a concave edge is the plain closest point).
        const double c1 = (q - p).normalized().dot(dir), c2 = (q2 - p).normalized().dot(dir);
        if ((q2 - p).norm() <= 2 * d && c2 > c1 + 1e-9) f = f2, q = q2;
      }
    }
    const std::int32_t o = out.mesh.add_node(q, core::NodeClass::on(f)).value();
    outer_of[n] = o;
    out.outer_nodes.push_back(o);
    out.inner_of_outer.push_back(n);
    out.outer_normals.push_back(dir.allFinite() ? dir : core::Vec3::Zero());
  }
  for (const Quad& q : quads) {
    core::HexNodes h;
    std::array<std::int32_t, 4> top;
    for (int c = 0; c < 4; ++c) h[c] = q.nodes[c], top[c] = outer_of[q.nodes[c]], h[c + 4] = top[c];
    out.mesh.add_hex(h, 1);
    out.outer_quads.push_back(top);
    ++out.pillow_hexes;
  }
  return out;
}

}  // namespace vorohex::grid::detail
