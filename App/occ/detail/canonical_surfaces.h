// Faces stored as B-spline surfaces that are cylinders to within a small tolerance - CAD
// systems and translators export some turned faces so, often one half of a boss as a cylinder
// and the other half as a B-spline (HexMe i12) - given the cylinder they approximate. Used
// when a solid is read (occ/shape_io.cpp, after elementary_surfaces.h): the schemes (a
// sweep's or multisweep's sides parallel to its axis) and the cuts at concave edges (a cut
// along the cylinder through such a face: OCCT's splitter loses the piece between a cylinder
// and a B-spline 5e-5 off it) see a cylinder where there is one.
#pragma once

#include <TopoDS_Solid.hxx>

namespace vorohex::occ::detail {

struct CanonicalResult {
  TopoDS_Solid solid;       // the converted solid (a new one; the input is not modified)
  int converted = 0;        // faces given a cylinder; with `planes` 0: `solid` is null
  int snapped = 0;          // of those, given the very cylinder of another face of the solid
  int planes = 0;           // faces given the plane they are (B-spline planes)
  double deviation = 0;     // the largest distance of a converted face's samples from its cylinder
  double volume_bound = 0;  // what the volume may change by: sum of deviation x area
};

// Each B-spline (or Bezier) face whose normals are all perpendicular to one direction and
// whose points lie on a circle about one axis, to within `tolerance` (model units), at every
// sample of its parameter range, becomes that cylinder; where an analytic cylinder of the
// solid lies within `tolerance` of it, that very cylinder (same axis and radius, so that
// OCCT unifies the two). Faces that go all the way round (a seam) are left as they are. Each
// edge of a converted face gets its curve on the cylinder by projection, with the tolerance
// that covers it. Faces, edges and vertices keep their order (the names users see).
CanonicalResult canonical_surfaces(const TopoDS_Solid& solid, double tolerance);

}  // namespace vorohex::occ::detail
