// Faces stored as B-spline surfaces that are cylinders or planes to within a small
// tolerance given those surfaces. CAD systems and translators export some faces so: one half
// of a boss as a cylinder and the other as a B-spline (HexMe i12), every face of a NURBS
// export. Used when a solid is read (occ/shape_io.cpp, after elementary_surfaces.h): the
// schemes (a sweep's sides parallel to its axis) and the cuts at concave edges (a cut along
// a cylinder through such a face: OCCT's splitter loses the piece between the cylinder and
// a B-spline 5e-5 off it) see a cylinder where there is one.
#pragma once

#include <TopoDS_Solid.hxx>

namespace vorohex::occ::detail {

struct CanonicalResult {
  TopoDS_Solid solid;       // the converted solid (a new one; the input is not modified)
  int converted = 0;        // faces given a cylinder; with `planes` 0: `solid` is null
  int snapped = 0;          // of those, given the very cylinder of another face of the solid
  int planes = 0;           // faces given the plane they are (B-spline planes)
  double deviation = 0;     // the largest distance of a converted face's samples from its surface
  double volume_bound = 0;  // what the volume may change by: sum of deviation x area
};

// Each B-spline (or Bezier) face that is planar, or whose normals are all perpendicular to
// one direction and whose points lie on a circle about one axis, to within
// `relative_tolerance` times the solid's size (its bounding box's diagonal) at every sample
// of its parameter range, becomes that plane or cylinder; where an analytic cylinder of the
// solid lies within that tolerance of it, that very cylinder (same axis, radius and seam, so
// that OCCT unifies the two). A face that goes all the way round gets its seam where its
// seam edge is. Each edge of a converted face gets its curve on the new surface by
// projection, with the tolerance that covers it. Faces, edges and vertices keep their order
// (the names users see). Nothing is done to a solid without B-spline faces.
CanonicalResult canonical_surfaces(const TopoDS_Solid& solid, double relative_tolerance);

}  // namespace vorohex::occ::detail
