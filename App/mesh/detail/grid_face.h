// Transfinite (mapped) quad grids on four-sided faces, from their boundary nodes: the
// source and target of sweeps, and the mapped faces of face sets.
#pragma once

#include <vector>

#include "core/geometry.h"
#include "core/ids.h"
#include "mesh/quad_face.h"
#include "occ/solid.h"

namespace vorohex::mesh::detail {

// The inner nodes of the transfinite grid on a four-sided face whose boundary nodes are
// `loop` in loop order (n0, n1, n0, n1 segments per side), row by row (i fastest),
// projected onto the face when it is curved.
std::vector<core::Vec3> grid_inner_nodes(const occ::Solid& solid, core::FaceId face,
                                         const std::vector<core::Vec3>& loop, int n0, int n1);

// The grid as a QuadFaceMesh (the loop, then the inner nodes; quads turning as the loop
// does), with its 2-D quality measured on the face.
QuadFaceMesh grid_face(const occ::Solid& solid, core::FaceId face,
                       const std::vector<core::Vec3>& loop, int n0, int n1);

}  // namespace vorohex::mesh::detail
