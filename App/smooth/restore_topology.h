// Restoring the original topology (paper §5.2): a mesh made sub-volume by sub-volume is
// classified on the entities of the glued sub-volumes, among them the decomposition faces
// that mean nothing to the user. Each node is moved to the class it has on the original
// solid: nodes on decomposition faces (and their edges and vertices inside the solid)
// become interior, nodes on pieces of split model faces and edges go to the original face
// or edge, so that smoothing frees the former and slides the latter on the real CAD.
#pragma once

#include "core/hex_mesh.h"
#include "occ/solid.h"

namespace vorohex::smooth {

struct RestoreStats {
  std::size_t interior = 0;  // nodes that were on a decomposition entity, now interior
  std::size_t on_faces = 0, on_edges = 0, on_vertices = 0;  // boundary nodes after restoring
  std::size_t reclassified = 0;  // nodes off the original face of their piece's face, moved
};

// `mesh` is classified on `pieces` (glued sub-volumes of `original`, occ::glue_solids);
// afterwards it is classified on `original`. An entity of `pieces` lies on an entity of
// `original` when its sample points are within `tolerance` (model units) of it.
RestoreStats restore_topology(core::HexMesh& mesh, const occ::Solid& pieces,
                              const occ::Solid& original, double tolerance);

}  // namespace vorohex::smooth
