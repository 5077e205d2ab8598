// The fallback for a solid no structured scheme accepts: a tetrahedral mesh of the solid
// (CGAL's Delaunay refinement on OCCT's triangulation of its boundary, every model edge
// kept as a feature), each tetrahedron split into four hexahedra, and every boundary node
// moved onto the CAD entity it approximates (vertex, edge or face). Always all-hex; the
// elements are of the quality such splits give (scaled Jacobian rarely above 0.7), so the
// pipeline reports it as a fallback.
#pragma once

#include <cstddef>
#include <vector>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"
#include "core/progress.h"
#include "occ/solid.h"

namespace vorohex::mesh {

struct TetSplitOptions {
  double size = 1.0;                 // target hexahedron edge length, model units (> 0)
  std::size_t max_hexes = 50000000;  // more is refused before the split (> 0)
  void validate() const;             // throws std::invalid_argument naming the bad field
};

struct TetSplitResult {
  core::HexMesh mesh;
  std::size_t tetrahedra = 0;
  bool ok = false;
  std::vector<core::Diagnostic> diagnostics;
};

TetSplitResult tet_split(const occ::Solid& solid, const TetSplitOptions& options,
                         const core::Progress& progress = {});

}  // namespace vorohex::mesh
