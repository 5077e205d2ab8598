// The CAD entity a point lies on, for meshers that place nodes by geometry (multisweep,
// revolve) and classify them afterwards.
#pragma once

#include "core/geometry.h"
#include "core/hex_mesh.h"
#include "occ/solid.h"

namespace vorohex::mesh::detail {

// Within `tol`: a vertex of the solid, else an edge, else a face; else interior. `hint`
// (the answer for a neighbouring point) is tried first among edges and faces, which saves
// the search when it holds.
core::NodeClass cad_entity_at(const occ::Solid& solid, const core::Vec3& p, double tol,
                              core::NodeClass hint = core::NodeClass::interior());

}  // namespace vorohex::mesh::detail
