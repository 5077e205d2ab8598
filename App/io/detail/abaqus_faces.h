// The numbering of boundary quads (core::boundary_faces) in Abaqus/CalculiX files.
#pragma once

namespace vorohex::io::detail {

// Abaqus/CalculiX face number (1..6, "S1".."S6") of a core::kHexFaces index: C3D8 and C3D20
// faces are 1-2-3-4, 5-8-7-6, 1-5-6-2, 2-6-7-3, 3-7-8-4, 4-8-5-1 (1-based, VTK order).
int abaqus_face_number(int hex_face);

}  // namespace vorohex::io::detail
