// The boundary quads of a hex mesh: hexahedron faces that belong to no other hexahedron.
#pragma once

#include <cstdint>
#include <vector>

#include "core/hex_mesh.h"

namespace vorohex::io::detail {

struct BoundaryFace {
  std::int32_t hex = 0;  // 0-based hexahedron index
  std::int8_t face = 0;  // index into core::kHexFaces (outward normal)
};

// In hexahedron order, then face order.
std::vector<BoundaryFace> boundary_faces(const core::HexMesh& mesh);

// Abaqus/CalculiX face number (1..6, "S1".."S6") of a core::kHexFaces index: C3D8 and C3D20
// faces are 1-2-3-4, 5-8-7-6, 1-5-6-2, 2-6-7-3, 3-7-8-4, 4-8-5-1 (1-based, VTK order).
int abaqus_face_number(int hex_face);

}  // namespace vorohex::io::detail
