// The grid mesher's core on a locally refined grid (grid/detail/refine.h), for parts with
// walls thinner than the uniform grid's cells (where the uniform core leaves most of the
// solid to the pillow layer, or falls apart at thin connections). Level by level, the
// cells the boundary passes near (a corner nearer than their size) with no core cell of
// their level within two cells, nor of the level before within one, are refined by thirds.
// The core is then chosen as on the uniform grid (core_cells.h): hexahedra whose corners
// are inside the solid (OCCT's classifier, one call per set of points joined by grid edges
// that cannot cross the boundary) and farther than margin times their cell's size from it
// (the tessellation's chord error added), made a manifold (hexahedra at a pinched edge or
// vertex of its boundary dropped) and reduced to its largest face-connected part.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "core/progress.h"
#include "grid/detail/grid_frame.h"
#include "grid/detail/refine.h"
#include "occ/solid.h"
#include "occ/tessellate.h"

namespace vorohex::grid::detail {

struct AdaptiveCoreOptions {
  double size = 1;                  // the base grid's cell size (the frame's)
  double margin = 0.5;              // core corners farther than margin * their cell's size
  double deflection = 0;            // the tessellation's chord error
  int max_level = 2;                // refinements by thirds (0: the uniform grid)
  std::size_t max_cells = 150'000;  // no level is refined past this many hexahedra in all
};

struct AdaptiveCore {
  RefinedGrid grid;
  std::vector<std::array<std::int32_t, 8>> core;  // the core's hexahedra (grid.points)
  double core_volume = 0;
  double left_out_volume = 0;  // core hexahedra away from the largest part, dropped
  std::size_t removed_for_manifold = 0, removed_components = 0;
  std::size_t classifier_calls = 0;
  int levels_used = 0;  // the finest level of any hexahedron
  bool budget_reached = false;
};

AdaptiveCore adaptive_core(const GridFrame& frame, const occ::Solid& solid,
                           const occ::Tessellation& tess, const AdaptiveCoreOptions& options,
                           const core::Progress& progress = {});

}  // namespace vorohex::grid::detail
