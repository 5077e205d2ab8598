// A second pillow layer under the boundary of a hex mesh, inserted where the first one left
// hexahedra that no smoothing untangles: a hex with two of its faces on the boundary across a
// model edge (a "doublet": where the two faces meet at nearly 180 degrees, or bend inwards,
// the hex's own angle there must be flat or reflex) or squeezed between a feature chain and
// the core. Every boundary node gets an interior twin a fraction of the way towards its
// hexahedra; the hexahedra take the twins, and each boundary quad becomes a new hexahedron
// between its twins and itself. Boundary nodes keep their place and their classification,
// so the new boundary is the old one; each new hexahedron has exactly one boundary quad.
#pragma once

#include <cstddef>
#include <vector>

#include "core/hex_mesh.h"

namespace vorohex::grid {

struct BoundaryPillowResult {
  std::size_t hexes_added = 0;
  std::size_t nodes_added = 0;
};

// `shrink` in (0, 1): how far each twin lies towards the inside. A boundary node with exactly
// one interior mesh edge has its twin on that edge at this fraction (a hexahedron with one
// boundary quad is then cut by the layer as by a plane of its own parameter space); any
// other goes towards the mean of its hexahedra's centroids by twice the fraction. Throws
// std::invalid_argument for a shrink outside (0, 1).
BoundaryPillowResult pillow_boundary(core::HexMesh& mesh, double shrink = 0.3);

// The hexahedra with two boundary quads across an edge whose outward normals differ by less
// than `max_turn_degrees`: the two faces lie nearly flat, so the hexahedron's own angle at
// that edge is nearly 180 degrees and no smoothing opens it; the boundary pillow splits it
// (each new hexahedron has one boundary quad). Where a structured mesh meets a fillet's
// tangent edge: the top face and the last layer across the fillet.
std::size_t flat_doublets(const core::HexMesh& mesh, double max_turn_degrees);

}  // namespace vorohex::grid
