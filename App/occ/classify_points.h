// Exact point-in-solid classification with OCCT's solid classifier (for the grid mesher's
// core cells). The only OCCT-facing entry point of the grid stage.
#pragma once

#include <vector>

#include "occ/solid.h"

namespace vorohex::occ {

enum class PointState : char { inside, outside, on };

// One state per point; points within `tolerance` (model units) of the boundary are `on`.
// OCCT failures classify a point as `on` (never as inside).
std::vector<PointState> classify_points(const Solid& solid, const std::vector<Vec3>& points,
                                        double tolerance);

}  // namespace vorohex::occ
