// Uniform refinement of a conforming hexahedral mesh: every hexahedron becomes n x n x n by
// trilinear interpolation of its corners. Nodes on a shared edge or face are created once
// (keyed by the coarse nodes of that edge or face), so the result conforms wherever the
// input does, and a planar coarse quadrilateral stays planar.
#pragma once

#include "core/hex_mesh.h"

namespace vorohex::mesh::detail {

// The coarse nodes keep their indices and classes; new nodes are interior (the caller
// classifies them). Sub-volume ids are inherited.
core::HexMesh refine_uniformly(const core::HexMesh& coarse, int n);

// The node count refine_uniformly(coarse, n) gives, without building it.
std::size_t refined_node_count(const core::HexMesh& coarse, int n);

}  // namespace vorohex::mesh::detail
