// Planes around round holes that cross a part's other direction (a cross hole through a
// tube's wall, a hole along a block beside a boss standing on it): what a Cubit user webcuts
// with before sweeping. A hole has no concave edge (its edges are convex), so the cuts at
// concave edges never isolate it, and no one sweep takes a part whose holes run two ways.
// Cut off by four planes parallel to its axis, at about one and a half radii from it, the
// hole lies in a piece swept along its axis, and the rest sweeps the other way.
// Internal to App/decompose (the plane cuts' third try, docs/decomposition.md).
#pragma once

#include <vector>

#include "occ/solid.h"
#include "occ/split_solid.h"

namespace vorohex::decompose::detail {

// A plane normal . x = offset, parallel to the axis of the hole of model face `hole`.
struct HolePlane {
  core::Vec3 normal;  // unit
  double offset = 0;
  core::FaceId hole;          // a face of the hole it is around (the largest)
  occ::CutCylinder cylinder;  // the hole's
};

// The sets of planes to try, best first: for each direction holes run along (the direction
// whose holes have the most area first), the planes around the holes that do not run along it
// (those stay in a sweep along it); then the planes around every hole. Sets that would be
// empty or repeat an earlier one are left out, and so are those around a hole that another,
// narrower than the planes' box, crosses inside it (two crossing holes). A hole: the faces on one
// cylinder whose material is outside it and whose edges go all around it (a fillet's do not).
std::vector<std::vector<HolePlane>> hole_plane_sets(const occ::Solid& solid);

}  // namespace vorohex::decompose::detail
