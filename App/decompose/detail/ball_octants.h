// The corners where three convex round fillets of one radius meet at right angles: a box
// whose top and vertical edges are filleted (FreeCAD's fillet of all of them) has an octant of
// a ball at each top corner, whose round face OCCT makes one spherical face with three arcs
// and its pole. Cut at the fillets' feet (the planes across them, all axes at once), each
// corner is left as that octant: four faces, three planar ones meeting at right angles at the
// ball's centre and the sphere, which no scheme takes whole. Split like the corner of a cube
// (an inner cube at the centre, and three blocks each between one of its faces and the
// sphere, parted by the planes through its diagonal), it is four topological hexahedra, and
// the fillets' strips beside it, their caps imprinted with the same parting, are prismatic.
// Internal to App/decompose (the plane cuts' fourth try, docs/decomposition.md).
#pragma once

#include <vector>

#include "occ/solid.h"

namespace vorohex::decompose::detail {

// Each ball octant among `pieces` (four faces, one a sphere about a vertex of the piece at
// which the three planar faces meet at right angles, the three other vertices on the sphere)
// replaced by its four blocks, and the fillets' strips beside them by three (their volumes in
// `volume`, per piece); a piece OCCT does not split so is kept. Returns how many were split.
// `time_limit`: seconds for each split (> 0).
int split_ball_octants(std::vector<occ::Solid>& pieces, std::vector<double>& volume,
                       double time_limit);

}  // namespace vorohex::decompose::detail
