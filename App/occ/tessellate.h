// Linear approximation of a solid's boundary for stages that work on polyhedra (the
// Voronoi graph): triangles per face and polylines per edge, each tagged with the model
// entity it approximates. Node positions are shared: an edge polyline's points are exactly
// nodes of the triangulations of the faces it bounds.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "occ/solid.h"

namespace vorohex::occ {

struct TessellationOptions {
  double linear_deflection = 0.01;   // model units: max chord distance to the true geometry
  double angular_deflection = 0.35;  // radians: max angle between neighbouring normals
};

struct FaceTriangulation {
  FaceId face;
  std::vector<Vec3> nodes;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside the solid
};

struct Tessellation {
  // Indexed by id value (index 0 unused), so faces[f.value()].face == f.
  std::vector<FaceTriangulation> faces;
  // Points from edge_first_vertex to edge_last_vertex; ends are the vertex points.
  // A degenerated edge has its single point.
  std::vector<std::vector<Vec3>> edge_polylines;
  std::string error;  // empty on success
  bool ok() const { return error.empty(); }
};

// Meshes the solid's faces with OCCT's incremental mesher (the triangulation is stored on
// the shape, as FreeCAD does) and reads it back. A triangulation left on the shape by an
// earlier call is removed first, so the result depends on the options only. OCCT failures
// become `error`.
Tessellation tessellate(const Solid& solid, const TessellationOptions& options);

}  // namespace vorohex::occ
