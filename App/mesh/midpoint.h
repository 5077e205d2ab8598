// Midpoint subdivision of a convex polyhedron (planar faces, straight edges). Nodes: the
// model vertices, a midpoint per edge, a centre per face and the cell centre. Where every
// vertex has three edges (tetrahedron, cube, dodecahedron, prisms) each vertex gets one
// hexahedron (vertex, its three edge midpoints, its three face centres, the cell centre);
// otherwise the cell is split into tetrahedra and each tetrahedron into four hexahedra: of
// the cell centre, a face centre and an edge; of the cell centre over each face's fan of
// triangles; or cones from one vertex over the faces away from it - whichever gives the
// best minimum scaled Jacobian (a square pyramid, two tetrahedra along a base diagonal: 0.5
// instead of 0.17). The coarse hexahedra are then refined n x n x n by
// trilinear interpolation to reach the target size (one n for all, so the mesh conforms).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"
#include "core/mesh_domain.h"
#include "core/progress.h"
#include "mesh/map_block.h"

namespace vorohex::mesh {

struct MidpointOptions {
  double size = 1.0;         // target edge length, model units (> 0)
  int max_intervals = 1000;  // refinement factor n limit; more is refused (> 0)
  void validate() const;     // throws std::invalid_argument naming the bad field
};

// Convex with planar faces, straight edges and one wire per face; the reason names the
// first entity that is not.
Applicability midpoint_applicable(const core::MeshDomain& solid);

struct MidpointEstimate {
  bool per_vertex = false;  // one coarse hexahedron per vertex (else via tetrahedra)
  int subdivisions = 0;     // n
  std::size_t coarse_hexes = 0, nodes = 0, hexes = 0;  // exactly what midpoint() produces
};
MidpointEstimate midpoint_evaluate(const core::MeshDomain& solid, const MidpointOptions& options);

struct MidpointResult {
  core::HexMesh mesh;
  bool per_vertex = false;
  std::string variant;  // how the cell was cut into coarse hexahedra, in words
  int subdivisions = 0;
  bool ok = false;
  std::vector<core::Diagnostic> diagnostics;
};

MidpointResult midpoint_subdivide(const core::MeshDomain& solid, const MidpointOptions& options,
                                  const core::Progress& progress = {});

// Below this minimum scaled Jacobian before smoothing a midpoint subdivision is poor: the
// mesher tries the solid's decomposition first and keeps whichever meshes better (a block
// with chamfered top edges: 0.07, where a block and a tapered slab give 0.58; HexMe's
// convex polyhedra start at 0.34).
constexpr double kPoorMidpointQuality = 0.2;

// The smallest scaled Jacobian of the coarse hexahedra (unrefined: what bounds the refined
// mesh's); 1 where the solid is refused.
double midpoint_coarse_quality(const core::MeshDomain& solid);

}  // namespace vorohex::mesh
