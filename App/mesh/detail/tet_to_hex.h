// Splitting tetrahedra into hexahedra: each tetrahedron into four, one per corner (the
// corner, its three edge midpoints, its three face centroids and the tetrahedron's
// centroid). Midpoints and centroids of shared edges and faces are created once, so a
// conforming tetrahedral mesh gives a conforming hexahedral one.
#pragma once

#include <array>
#include <vector>

#include "core/hex_mesh.h"

namespace vorohex::mesh::detail {

struct TetSplitNodes {
  // For every node the split created (index - first_new): the sorted nodes of the
  // tetrahedron edge {a, b, -1} or face {a, b, c} it is the midpoint or centroid of;
  // {-1, -1, -1} for a tetrahedron's centroid.
  std::size_t first_new = 0;
  std::vector<std::array<int, 3>> origin;
};

// tets: node indices into mesh (any orientation). New nodes are interior; the caller
// classifies them.
TetSplitNodes split_tetrahedra(core::HexMesh& mesh, const std::vector<std::array<int, 4>>& tets);

// Adds hexahedron h, with nodes 1<->3 and 5<->7 swapped if needed so that its corner at
// node 0 is positive.
void add_hex_positive_at_corner0(core::HexMesh& mesh, core::HexNodes h,
                                 std::int32_t sub_volume = 0);

}  // namespace vorohex::mesh::detail
