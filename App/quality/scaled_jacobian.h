// The Verdict hexahedron scaled Jacobian: the minimum, over the 8 corners and the centre,
// of the determinant of the Jacobian with column-normalised edge vectors. 1 for a cube,
// <= 0 for an inverted element; a collapsed edge (zero-length edge vector) gives 0, i.e.
// invalid, never "perfect".
#pragma once

#include <array>
#include <vector>

#include "core/geometry.h"
#include "core/hex_mesh.h"

namespace vorohex::quality {

double scaled_jacobian(const std::array<core::Vec3, 8>& corners);

// One value per hexahedron of the mesh (computed in parallel for large meshes).
std::vector<double> scaled_jacobians(const core::HexMesh& mesh);

// Exact volume of the trilinear hexahedron (signed; negative when inverted).
double hex_volume(const std::array<core::Vec3, 8>& corners);

}  // namespace vorohex::quality
