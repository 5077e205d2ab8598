// det J of an 8-node (trilinear) hexahedron at its 2 x 2 x 2 Gauss points, where a solver
// such as CalculiX integrates C3D8 and refuses a non-positive value ("nonpositive jacobian
// determinant"). The Verdict scaled Jacobian judges the corners and the centre only, so a
// badly shaped hex can pass it and still fail here (measured on fallback meshes).
#pragma once

#include <array>

#include "core/geometry.h"

namespace vorohex::quality {

// The smallest det J over the 8 Gauss points (model units^3 / 8); corners in VTK order.
double linear_hex_gauss_min_det(const std::array<core::Vec3, 8>& corners);

}  // namespace vorohex::quality
