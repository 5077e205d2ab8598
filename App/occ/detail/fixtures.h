// Deliberately broken or unusual shapes written to files, for the reader's tests (tests may
// not include OCCT headers). Defined in occ/primitives.cpp.
#pragma once

#include <string>

namespace vorohex::occ::detail {

enum class Fixture {
  open_box_shell,           // a shell of five faces of the unit box (one face missing)
  closed_box_shell,         // the six faces of the unit box as a shell, not a solid
  two_boxes,                // a compound of two disjoint unit boxes
  touching_boxes,           // unit boxes at x = 0 and x = 1 (separate shapes touching at x = 1)
  stacked_boxes,            // a 2 x 1 x 1 box with a unit box on top at x in [0.5, 1.5]
  overlapping_boxes,        // unit boxes at x = 0 and x = 0.5
  box_faces,                // a compound of three loose faces of the unit box
  bad_tolerance_box,        // the unit box with one vertex moved 1e-4 off its edges, tolerance 1e-7
  self_intersecting_prism,  // a bow-tie outline (its edges cross at (1, 0.5)) extruded by 1
  edge_touching_boxes,      // unit boxes at the origin and at (1, 1, 0): one common edge
  vertex_touching_boxes,    // unit boxes at the origin and at (1, 1, 1): one common vertex
  // Turned faces stored as surfaces of revolution of a line (OCCT's
  // ShapeCustom::ConvertToRevolution), as some CAD systems export them:
  revolved_cylinder,  // a cylinder of radius 2 and height 5 on the z axis
  revolved_cone,      // a cone frustum, radii 3 (z = 0) and 1 (z = 4), on the z axis
  // Every face stored as a B-spline surface (OCCT's BRepBuilderAPI_NurbsConvert), as some
  // translators export them:
  bspline_half_cylinder,  // half a cylinder of radius 2 and height 5 on the z axis (y >= 0)
  bspline_tube,           // a tube, radii 1 and 2, height 5, on the z axis (closed faces, seams)
  bspline_flanged_pipe,   // a pipe (radii 6 and 10, 40 long) on a flange (radius 20, 6 thick)
};

// Writes the fixture; the format comes from the extension (.brep/.brp or .step/.stp).
bool write_fixture(Fixture kind, const std::string& path);

}  // namespace vorohex::occ::detail
