// The grid mesher's hexahedra before feature capture: the core cells, and one pillow layer
// between the core's boundary and the CAD surface. Every boundary node of the core gets an
// outer node at its closest point on the CAD boundary (classified on that face); every
// boundary quad of the core becomes a hexahedron with its four outer nodes. The core's
// boundary is a closed manifold (core_cells), so the layer conforms and closes.
#pragma once

#include <array>
#include <vector>

#include "core/hex_mesh.h"
#include "core/mesh_domain.h"
#include "grid/detail/core_cells.h"
#include "grid/detail/grid_frame.h"

namespace vorohex::grid::detail {

// A hexahedron's face by its sorted node indices (faces of two hexahedra match when equal).
using QuadKey = std::array<std::int32_t, 4>;
struct QuadKeyHash {
  std::size_t operator()(const QuadKey& k) const {
    std::size_t h = 0;
    for (std::int32_t v : k) h = h * 0x9E3779B97F4A7C15ull + std::size_t(v);
    return h;
  }
};
QuadKey quad_key(const std::array<std::int32_t, 8>& hex, int face);  // face: kHexFaces index

struct PillowMesh {
  core::HexMesh mesh;
  std::vector<std::int32_t> outer_nodes;                 // nodes on the CAD boundary
  std::vector<std::array<std::int32_t, 4>> outer_quads;  // outward, one per pillow hex
  std::vector<std::int32_t> inner_of_outer;              // per outer node: its core node
  std::vector<core::Vec3> outer_normals;  // per outer node: mean normal of its core quads
  std::size_t core_hexes = 0, pillow_hexes = 0;
};

PillowMesh pillow_mesh(const GridFrame& frame, const CoreCells& core,
                       const core::MeshDomain& solid);

// The same on any core of hexahedra (a refined grid's, grid/detail/refine.h): `hexes` index
// `points` (VTK order, positive), the core's boundary a closed manifold; mesh nodes are
// numbered in the order the hexahedra first use them. `axes`: the grid's, each of the six
// directions counted once in a node's outward direction.
PillowMesh pillow_mesh(const std::vector<core::Vec3>& points,
                       const std::vector<std::array<std::int32_t, 8>>& hexes,
                       const std::array<core::Vec3, 3>& axes, const core::MeshDomain& solid);

}  // namespace vorohex::grid::detail
