// Planes that leave the concave round fillets along a floor on strips that sweep: a pocket
// whose floor edges are rounded, a rectangular boss whose root is. Each such fillet is a
// cylinder tangent to the floor and to a wall at right angles to it; where two of them meet
// at a corner their surfaces cross along a mitre. No plane at a concave edge separates them
// (a fillet's edges are tangent), and the planes of the walls and the floor would each leave
// a knife edge where the fillet touches them. Cut across the floor at the fillet's foot (at
// right angles to the floor and the fillet: through its axis), and as far beyond the wall as
// the foot is inside it, each fillet lies on a strip whose section is the wall's and the
// floor's corner rounded; at a corner the two strips meet along the plane of the mitre, cut
// only between the crossing of their feet's planes and the crossing of their far planes.
// Each strip is then a sweep from mitre to mitre, and the rest blocks (the pieces beside a
// strip split where the other strips end: its sweep's linking sides carry their imprints,
// mesh/sweep.h `imprinted`). Where the pocket's corners are rounded too, the fillet turns
// round each corner on a surface of revolution, and the strip on a quarter ring (StripCylinder
// sectors, ended by planes through the corner's axis), swept round that axis.
// Internal to App/decompose (the plane cuts' fifth try, docs/decomposition.md).
#pragma once

#include <vector>

#include "occ/solid.h"
#include "occ/split_solid.h"

namespace vorohex::decompose::detail {

// A cut surface: the plane normal . x = offset, or the quad `quad` (bounded).
struct StripPlane {
  core::Vec3 normal;  // unit
  double offset = 0;
  core::FaceId face;                // the fillet
  std::vector<core::EdgeId> edges;  // its foot (across), its wall's foot (beyond), the mitre
  // `corner`: the plane through a rounded corner's axis where a straight strip meets the
  // corner's.
  enum Kind { across, beyond, mitre, corner } kind = across;
  std::vector<core::Vec3> quad;  // its corners where bounded (mitres, corners, and the
                                 // straight strips' planes between rounded corners)
};

// At a pocket's rounded corner (its vertical edges filleted too: the floor fillet turns round
// the corner on a surface of revolution about the corner's axis), the strip turns on a sector
// of a ring: between the cylinder through the fillet's foot on the floor and the one as far
// beyond the corner's wall, from one straight strip's end to the other's.
struct StripCylinder {
  occ::CutCylinder surface;  // a sector (`angle` < 2 pi)
  core::FaceId face;         // the corner's fillet
  core::EdgeId edge;         // its foot (inner) or its wall's foot (beyond)
  bool beyond = false;
};

struct FilletStrips {
  std::vector<StripPlane> planes;
  std::vector<StripCylinder> cylinders;
  // The planar faces the fillets are tangent to (floors and walls): their own planes are no
  // cut (each would leave a knife edge along a fillet).
  std::vector<core::FaceId> tangent_faces;
  // The fillets on strips: their cylinders are no cut either (their mitres are concave edges).
  std::vector<core::FaceId> fillets;
};

// The planes of the fillets of `solid` that meet another at a mitre on a common floor (empty
// when none does).
FilletStrips fillet_strips(const occ::Solid& solid);

}  // namespace vorohex::decompose::detail
