// Which way each sweep among glued sub-volumes goes (mesh_sub_volumes): a face two of them
// share, where the quad mesher meshes it freely, must be meshed once and taken as it is by
// the other. A sweep meshes its source; its target gets the far end's nodes.
#pragma once

#include <vector>

#include "mesh/detail/sub_volume_part.h"

namespace vorohex::mesh::detail {

// Turns the sweeps among `parts` round where that makes their shared faces match:
// - a face one sweep takes as its source, another as its target: both take it as source;
// - two targets on one face meshed freely: both take it as source;
// - sweeps meeting two by two at such faces, in a row or a ring: from one of them on, each
//   takes the face it shares with the one before as its source (a ring's last target is its
//   first source: the caller gives it);
// - a target on a face a multisweep meshes as a cap: it becomes the source.
void orient_sweeps(std::vector<Part>& parts);

}  // namespace vorohex::mesh::detail
