// What the part's geometry allows: along a convex edge whose faces meet inside the part at an
// angle theta below 90 degrees, every hexahedron with a face on each of the two faces has a
// corner whose two edges across the model edge lie in those faces, so its scaled Jacobian is
// at most sin(theta) (the determinant of three unit vectors, one along the edge, is at most
// the sine of the angle between the other two's components across it); hexahedra that share
// the edge split theta and do worse. So no hex mesh that follows the edge, whatever the
// mesher, does better there. HexMe's n13 (an edge at 10 degrees) is meshed at exactly 0.174;
// i07 has two edges where a plane and a turned face meet at 0 degrees (knife edges).
// (A corner of three edges bounds only a hexahedron with its corner there along all three:
// a mesh may put several there, so corners are not reported.)
#pragma once

#include <vector>

#include "core/ids.h"
#include "occ/solid.h"

namespace vorohex::quality {

struct SharpEdge {
  core::EdgeId edge;
  double angle = 0;  // degrees: the smallest angle inside the part between its two faces
  double bound = 1;  // sin(angle): the best scaled Jacobian of a hexahedron along it
};

struct SharpEdges {
  std::vector<SharpEdge> edges;  // sharpest first
  // The smallest bound of all (1 when there is none below `below`).
  double bound() const;
};

// Convex edges whose bound is below `below` (measured at the middle, and at seven points
// along those sharper than 100 degrees there).
SharpEdges sharp_edges(const occ::Solid& solid, double below = 0.5);

}  // namespace vorohex::quality
