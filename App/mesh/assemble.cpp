#include "mesh/assemble.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <unordered_map>
#include <vector>

namespace vorohex::mesh {
namespace {

using core::NodeClass;
using core::Vec3;

// Nodes of the whole on CAD entities, bucketed by position (cells of the merge tolerance).
class BoundaryGrid {
 public:
  explicit BoundaryGrid(double cell) : cell_(cell) {}

  void add(const Vec3& p, std::int32_t node) { cells_[key(cell_of(p))].push_back(node); }

  // The node with class c within `tol` of p, or -1.
  std::int32_t find(const core::HexMesh& mesh, const Vec3& p, NodeClass c, double tol) const {
    const std::array<std::int64_t, 3> k = cell_of(p);
    std::int32_t best = -1;
    double best_d = tol;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(key({k[0] + dx, k[1] + dy, k[2] + dz}));
          if (it == cells_.end()) continue;
          for (std::int32_t n : it->second) {
            const core::NodeId id(n);
            if (!(mesh.node_class(id) == c)) continue;
            const double d = (mesh.point(id) - p).norm();
            if (d <= best_d) best_d = d, best = n;
          }
        }
    return best;
  }

 private:
  std::array<std::int64_t, 3> cell_of(const Vec3& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x() / cell_)),
            static_cast<std::int64_t>(std::floor(p.y() / cell_)),
            static_cast<std::int64_t>(std::floor(p.z() / cell_))};
  }
  static std::uint64_t key(const std::array<std::int64_t, 3>& k) {
    // Hash of the cell; collisions only cost a few extra comparisons.
    return static_cast<std::uint64_t>(k[0]) * 73856093u ^
           static_cast<std::uint64_t>(k[1]) * 19349663u ^
           static_cast<std::uint64_t>(k[2]) * 83492791u;
  }

  double cell_;
  std::unordered_map<std::uint64_t, std::vector<std::int32_t>> cells_;
};

}  // namespace

AppendPartResult append_part(core::HexMesh& whole_mesh, const occ::Solid& whole,
                             const core::HexMesh& part_mesh, const occ::Solid& part,
                             std::int32_t sub_volume, double tolerance) {
  if (!(tolerance > 0) || !std::isfinite(tolerance))
    throw std::invalid_argument("append_part: the tolerance must be a positive length");
  const std::vector<int> ids[3] = {whole.part_ids(part, 0), whole.part_ids(part, 1),
                                   whole.part_ids(part, 2)};
  BoundaryGrid grid(tolerance * 4);
  for (std::size_t n = 0; n < whole_mesh.num_nodes(); ++n) {
    const core::NodeId id(static_cast<std::int32_t>(n));
    if (!whole_mesh.node_class(id).is_interior())
      grid.add(whole_mesh.point(id), static_cast<std::int32_t>(n));
  }
  AppendPartResult r;
  std::vector<std::int32_t> node_map(part_mesh.num_nodes());
  for (std::size_t n = 0; n < part_mesh.num_nodes(); ++n) {
    const core::NodeId id(static_cast<std::int32_t>(n));
    NodeClass c = part_mesh.node_class(id);
    if (!c.is_interior()) {
      const std::vector<int>& map = ids[c.dim];
      if (c.id < 1 || c.id >= static_cast<int>(map.size()) || map[c.id] == 0)
        throw std::invalid_argument("append_part: node " + std::to_string(n) +
                                    " names no entity of the part");
      c.id = map[c.id];
      const std::int32_t same = grid.find(whole_mesh, part_mesh.point(id), c, tolerance);
      if (same >= 0) {
        node_map[n] = same;
        ++r.nodes_merged;
        continue;
      }
    }
    node_map[n] = whole_mesh.add_node(part_mesh.point(id), c).value();
    ++r.nodes_added;
  }
  for (const core::HexNodes& hex : part_mesh.hexes()) {
    core::HexNodes mapped;
    for (int i = 0; i < 8; ++i) mapped[i] = node_map[hex[i]];
    whole_mesh.add_hex(mapped, sub_volume);
  }
  return r;
}

}  // namespace vorohex::mesh
