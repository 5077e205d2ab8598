// Faces stored as surfaces of revolution of a straight line - some CAD systems export every
// turned face so (HexMe i01, i06, i07, i13, i16) - given the cylinder or cone they are, with
// the same parametrisation, so every curve on them stays as it is. Used when a solid is read
// (occ/shape_io.cpp), so that the schemes and the cuts at concave edges see a cylinder where
// there is one, whatever system wrote the file.
#pragma once

#include <TopoDS_Solid.hxx>

namespace vorohex::occ::detail {

struct ElementaryResult {
  TopoDS_Solid solid;  // the converted solid (a new one; the input is not modified)
  int converted = 0;   // faces given a cylinder or cone; 0: `solid` is null
};

// Each face whose surface of revolution has a line in a plane through the axis as its
// meridian becomes a cylinder (line parallel to the axis) or a cone, when the new surface
// gives the same points as the old one at every sample of the face's parameter range (to
// 1e-9 of the face's size). Faces, edges and vertices keep their order (the names users
// see). Planes stored so (a line perpendicular to the axis) are left as they are: a plane
// is not parametrised by angle and radius.
ElementaryResult elementary_surfaces(const TopoDS_Solid& solid);

}  // namespace vorohex::occ::detail
