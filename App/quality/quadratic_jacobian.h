// Validity of a 20-node (serendipity) hexahedron: the determinant of its Jacobian at the
// 3 x 3 x 3 Gauss points, where a second-order solver integrates it. A curved element whose
// corners are fine can still fold near a mid-edge node; a non-positive determinant at a
// Gauss point makes the solver's stiffness wrong.
#pragma once

#include <array>

#include "core/geometry.h"

namespace vorohex::quality {

struct QuadraticJacobian {
  double min_det = 0;  // smallest det J over the 27 Gauss points (model units^3 / 8)
  double max_det = 0;  // largest
};

// nodes: 8 corners then 12 mid-edge nodes, VTK_QUADRATIC_HEXAHEDRON order (core/hex_mesh.h).
QuadraticJacobian quadratic_hex_jacobian(const std::array<core::Vec3, 20>& nodes);

}  // namespace vorohex::quality
