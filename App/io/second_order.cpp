#include "io/second_order.h"

#include <map>
#include <unordered_map>

#include "quality/quadratic_jacobian.h"

namespace vorohex::io {
namespace {

std::uint64_t edge_key(std::int32_t a, std::int32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

std::array<core::Vec3, 20> element_nodes(const core::HexMesh& mesh, std::size_t h,
                                         const core::MidEdgeNodes& mid) {
  std::array<core::Vec3, 20> p;
  for (int i = 0; i < 8; ++i) p[i] = mesh.points()[mesh.hexes()[h][i]];
  for (int i = 0; i < 12; ++i) p[8 + i] = mesh.points()[mid[i]];
  return p;
}

}  // namespace

SecondOrderStats make_second_order(core::HexMesh& mesh, const core::MeshDomain& domain,
                                   const std::vector<NamedGroup>& groups) {
  SecondOrderStats stats;
  const auto& hexes = mesh.hexes();
  // Which model entity each boundary mesh edge lies on: edges first, then face quads' sides.
  std::unordered_map<std::uint64_t, core::NodeClass> on;
  for (const NamedGroup& g : groups)
    if (g.dim == 1)
      for (const GroupEdge& e : g.edges) {
        const auto& ends = core::kHexEdges[e.edge];
        on[edge_key(hexes[e.hex][ends[0]], hexes[e.hex][ends[1]])] =
            core::NodeClass::on(core::EdgeId(g.id));
      }
  for (const NamedGroup& g : groups)
    if (g.dim == 2)
      for (const GroupFace& f : g.faces) {
        const auto& quad = core::kHexFaces[f.face];
        for (int i = 0; i < 4; ++i)
          on.emplace(edge_key(hexes[f.hex][quad[i]], hexes[f.hex][quad[(i + 1) % 4]]),
                     core::NodeClass::on(core::FaceId(g.id)));
      }

  std::unordered_map<std::uint64_t, std::int32_t> mid_of;
  std::vector<core::Vec3> straight;  // per new node: the straight midpoint
  std::vector<core::MidEdgeNodes> mid(hexes.size());
  const std::size_t first_mid = mesh.num_nodes();
  for (std::size_t h = 0; h < hexes.size(); ++h)
    for (int e = 0; e < 12; ++e) {
      const std::int32_t a = hexes[h][core::kHexEdges[e][0]], b = hexes[h][core::kHexEdges[e][1]];
      const std::uint64_t key = edge_key(a, b);
      auto it = mid_of.find(key);
      if (it == mid_of.end()) {
        const core::Vec3 m = (mesh.point(core::NodeId(a)) + mesh.point(core::NodeId(b))) / 2.0;
        core::NodeClass c = core::NodeClass::interior();
        core::Vec3 p = m;
        if (auto found = on.find(key); found != on.end()) {
          c = found->second;
          if (c.dim == 1) {
            p = domain.project_to_edge(core::EdgeId(c.id), m);
            ++stats.on_edges;
          } else {
            p = domain.project_to_face(core::FaceId(c.id), m);
            ++stats.on_faces;
          }
        }
        straight.push_back(m);
        it = mid_of.emplace(key, mesh.add_node(p, c).value()).first;
      }
      mid[h][e] = it->second;
    }
  stats.mid_nodes = mesh.num_nodes() - first_mid;

  // A projection that folds an element (a strongly curved face across a thin element) is
  // undone: the node goes back to the straight midpoint. It keeps its entity (it belongs to
  // that face's groups), so the CAD check measures how far off the CAD it now is.
  for (int round = 0; round < 3; ++round) {
    bool changed = false;
    for (std::size_t h = 0; h < hexes.size(); ++h) {
      if (quality::quadratic_hex_jacobian(element_nodes(mesh, h, mid[h])).min_det > 0) continue;
      for (std::int32_t n : mid[h]) {
        const core::Vec3& s = straight[n - first_mid];
        if ((mesh.point(core::NodeId(n)) - s).squaredNorm() > 0) {
          mesh.set_point(core::NodeId(n), s);
          ++stats.straightened;
          changed = true;
        }
      }
    }
    if (!changed) break;
  }
  mesh.set_mid_edge_nodes(std::move(mid));
  return stats;
}

}  // namespace vorohex::io
