// Where a plane cut's piece lies, for the merging (App/decompose/plane_cuts.cpp): on a hole's
// cylinder, in a fillet's strip, within a cylinder cut around a boss. Internal to App/decompose.
#pragma once

#include <vector>

#include "core/geometry.h"
#include "occ/solid.h"
#include "occ/split_solid.h"

namespace vorohex::decompose::detail {

// Whether a face of the piece lies on one of the holes' cylinders.
bool on_a_hole(const occ::Solid& piece, const std::vector<occ::CutCylinder>& holes);

// The strip between two parallel planes normal . x = lo and = hi (a fillet's strip, between the
// plane across its foot and the plane beyond its wall); `along`: the fillet's box.
struct Band {
  core::Vec3 normal;
  double lo = 0, hi = 0;
  core::BoundingBox along;
};

// Whether every vertex of the piece lies in the band.
bool within(const occ::Solid& piece, const Band& b);

// Whether the piece's box meets the band's fillet's.
bool beside_fillet(const occ::Solid& piece, const Band& b);

// Whether every vertex of the piece lies within cylinder c (a piece of the boss a cylinder
// through a fillet's foot cut out of its plate).
bool within(const occ::Solid& piece, const occ::CutCylinder& c);

}  // namespace vorohex::decompose::detail
