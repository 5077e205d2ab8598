// Joining the meshes of several solids glued at common faces (occ::Solid::part) into one
// mesh of the whole, conforming where the part meshes coincide on the shared faces.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/hex_mesh.h"
#include "occ/solid.h"

namespace vorohex::mesh {

struct AppendPartResult {
  std::size_t nodes_added = 0;   // new nodes of the whole
  std::size_t nodes_merged = 0;  // part nodes that became an existing node of the whole
};

// Appends `part_mesh`, classified on the entities of `part` (one of whole.part(k)), to
// `whole_mesh`, classified on the entities of `whole`: node classes are renumbered to
// `whole`, and a node on an entity the part shares with parts appended before (a common
// face, its edges and vertices) becomes the node already there with the same entity within
// `tolerance` (model units). Its hexes get `sub_volume`. Where the part meshes differ on a
// shared face, nothing is merged there; the validity check then names that face
// (non_conforming_interface).
AppendPartResult append_part(core::HexMesh& whole_mesh, const occ::Solid& whole,
                             const core::HexMesh& part_mesh, const occ::Solid& part,
                             std::int32_t sub_volume, double tolerance);

}  // namespace vorohex::mesh
