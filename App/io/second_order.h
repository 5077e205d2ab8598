// Second-order (20-node) hexahedra from a first-order mesh: one node in the middle of
// every mesh edge, shared by the hexahedra around it. A mesh edge along a model edge gets
// its node projected onto that edge, one on a model face onto that face (so the element
// follows the CAD's curvature); inner edges stay straight. Mid-edge nodes are classified
// on the entity they were put on, so the named groups and the CAD check include them.
#pragma once

#include <cstddef>
#include <vector>

#include "core/hex_mesh.h"
#include "core/mesh_domain.h"
#include "io/named_groups.h"

namespace vorohex::io {

struct SecondOrderStats {
  std::size_t mid_nodes = 0;     // nodes added
  std::size_t on_edges = 0;      // of which projected onto model edges
  std::size_t on_faces = 0;      // onto model faces
  std::size_t straightened = 0;  // projected, then put back straight (still classified
                                 // on the entity): the projection folded an element
};

// mesh: first order (its order() becomes 2); groups: named_groups(mesh, domain) of it,
// which say which mesh edges lie on which model edge or face.
SecondOrderStats make_second_order(core::HexMesh& mesh, const core::MeshDomain& domain,
                                   const std::vector<NamedGroup>& groups);

}  // namespace vorohex::io
