// Grid-based all-hex meshing for any closed solid (the pipeline's fallback, scheme `grid`):
//  1. a core grid aligned with the part (grid/detail/grid_frame.h) whose cells well inside
//     the solid are kept (exact classification by OCCT, grid/detail/core_cells.h);
//  2. one pillow layer from the core's boundary quads to the CAD surface (closest points);
//  3. feature capture: model vertices, then chains along model edges, then faces
//     (grid/detail/features.h), what could not be captured reported;
//  4. optimisation with nodes on their vertex, edge or face that never inverts an element
//     and never lowers the minimum scaled Jacobian (smooth::smooth_mesh: untangling, then
//     raising the worst elements).
// An inverted element left after step 4 is an error, never a result. With step 4 off (the
// pipeline smooths every mesh itself afterwards) the mesh is returned as it is and the
// caller's validity check judges it.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"
#include "core/progress.h"
#include "grid/composites.h"
#include "occ/solid.h"

namespace vorohex::grid {

struct GridOptions {
  double size = 1.0;  // target edge length of the core cells, model units (> 0)
  // Core cells keep every corner farther than core_margin * size from the boundary (> 0).
  double core_margin = 0.5;
  bool capture_features = true;  // false: outer nodes stay at their closest points
  // Where two edges of one face leave a vertex tangentially (a cusp), their chains share
  // nodes while within 0.3 cells of each other (grid/detail/features.h); the face's tip
  // narrower than that gets no quads. Off by default: on HexMe it raises i03's minimum
  // (0.001 -> 0.26) and breaks i19's and i09's meshes (docs/meshing.md), so the pipeline
  // uses it only to make a poor grid mesh again whose worst hexahedron is at a cusp.
  bool share_cusps = false;
  // Step 4 (smooth::SmoothOptions of the same names); 0 and 0 skip it.
  int laplacian_iterations = 20;
  int optimisation_passes = 10;
  double quality_target = 0.5;  // scaled Jacobian the optimisation aims for, in (0, 1]
  // Times the size is halved while the core holds less than min_core_share of the volume
  // (walls thinner than about three cells; min_core_share in [0, 1]) or falls apart into
  // pieces (a quarter of it or more left out), as long as the refined grid has about
  // max_refined_cells cells inside the solid (its volume over a cell's) and at most
  // max_grid_cells in its bounding box (the classification's arrays). A grid with no core
  // cell at all (no mesh) is halved on past max_refinements, within those cells.
  int max_refinements = 2;
  double min_core_share = 0.25;
  std::size_t max_refined_cells = 500'000;
  std::size_t max_grid_cells = 8'000'000;
  // Where the core is still thin or split after that: the grid refined locally by thirds,
  // up to max_levels times (0: never), near the walls thinner than about two cells
  // (grid/detail/adaptive_core.h), as long as the levels hold at most max_local_cells cells
  // in all; used when its core holds more of the volume.
  int max_levels = 2;
  std::size_t max_local_cells = 150'000;
  std::size_t max_hexes = 50'000'000;  // more is refused before the core is built (> 0)
  void validate() const;               // throws std::invalid_argument naming the bad field
};

struct GridStats {
  double size_used = 0;             // after refinements (the smallest cells')
  int local_levels = 0;             // local refinements by thirds used (0: a uniform grid)
  std::array<int, 3> grid_cells{};  // per axis
  std::string axes_from;            // "planar faces", "axis of revolution", "world axes"
  std::size_t core_hexes = 0, pillow_hexes = 0;
  std::size_t classifier_calls = 0;      // OCCT point classifications
  std::size_t removed_for_manifold = 0;  // core cells dropped so its boundary is a manifold
  int vertices = 0, vertices_captured = 0, edges = 0, edges_captured = 0, faces = 0,
      faces_captured = 0;
  double min_sj_before_optimisation = 0, min_sj = 0, mean_sj = 0;
  std::size_t inverted_before_optimisation = 0, inverted = 0;
  std::size_t features_missed = 0;  // vertices, edges and faces not captured
  double seconds_core = 0, seconds_pillow = 0, seconds_features = 0, seconds_optimisation = 0;
  // Largest deviation of the boundary on the composites from the real surface (after the
  // optimisation; -1 when not measured: no composite, or step 4 off).
  double absorbed_deviation = -1;
  // Where the model's cusps are (vertices at which two edges of one face leave tangentially).
  std::vector<core::Vec3> cusp_points;
};

struct GridResult {
  core::HexMesh mesh;
  bool ok = false;  // a mesh was made (without inverted elements, if optimised)
  GridStats stats;
  std::vector<core::Diagnostic> diagnostics;
  // The absorbed features and their composites (to measure the deviation again after a
  // later smoothing), and the FreeCAD names of the absorbed entities.
  SmallFeatures absorbed;
  std::vector<std::string> absorbed_names;
};

GridResult grid_mesh(const occ::Solid& solid, const GridOptions& options,
                     const core::Progress& progress = {});

}  // namespace vorohex::grid
