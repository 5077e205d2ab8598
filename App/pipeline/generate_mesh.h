// The whole pipeline as one straight sequence of calls (like Gmsh's GenerateMesh):
// validate options -> choose a scheme -> mesh -> check validity. Later stages (Voronoi
// graph, decomposition, smoothing) slot in here in order.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"
#include "core/progress.h"
#include "core/size_field.h"
#include "grid/composites.h"
#include "io/named_groups.h"
#include "occ/solid.h"
#include "quality/check_mesh.h"
#include "smooth/smooth_mesh.h"
#include "voronoi/voronoi_graph.h"

namespace vorohex::pipeline {

struct MeshOptions {
  double size = 0;  // target edge length, model units; 0 = diagonal / 20
  // Local sizes: smaller target lengths at faces, edges or vertices ("Face7", "Edge3",
  // "Vertex2"; model units), graded into the global size: at distance d from the entity the
  // target is local + size_grading * d, never above `size` (core/size_field.h). The map,
  // sweep, multisweep and revolve schemes and the decomposition follow them; midpoint and
  // the fallbacks mesh at the global size and say so.
  std::vector<core::LocalSize> local_sizes;
  double size_grading = 0.3;           // growth of the size per unit distance (> 0, at most 10)
  std::size_t max_hexes = 50'000'000;  // refused up front when the prediction exceeds it
  smooth::SmoothOptions smoothing;     // global smoothing; 0 iterations and 0 passes = off
  quality::CheckOptions check;         // tolerances of the final validity check
  // Where no structured scheme applies: the grid mesher (grid/grid_mesh.h; a warning says
  // so); false refuses such solids instead.
  bool fallback = true;
  // The fallback: "grid" (core grid, pillow layer, feature capture) or "tet-split" (CGAL
  // tetrahedra each split into four hexahedra; kept only for comparison).
  std::string fallback_scheme = "grid";
  // On a machine with two cores or more, the fallback (with the tet split's second chance)
  // runs beside the decomposition, in a second child process, and is taken when the
  // decomposition gives no mesh (else killed): what the user waits for is the longer of the
  // two, not their sum; likewise the tet split's second chance beside the grid's smoothing
  // and check. The result is the same either way; false runs them one after the other, as
  // on one core.
  bool fallback_beside = true;
  // The single-solid schemes tried in this order, the first that applies meshes the solid:
  // "map" (topological hexahedron), "sweep" (one-to-one), "multisweep" (prismatic, many
  // levels), "revolve" (solid of revolution), "midpoint" (convex polyhedron); "grid" (the
  // fallback's grid mesher, for any solid) only when named. Leaving one out forbids it
  // (the decomposition and the fallback come after them all).
  std::vector<std::string> schemes = {"map", "sweep", "multisweep", "revolve", "midpoint"};
  // Where no single scheme applies, first cut the solid into sub-volumes along its Voronoi
  // graph (paper §4) and mesh those into one conforming mesh (§5); the fallback (if on)
  // takes what that cannot mesh. The exact cuts at concave edges, then the graph and its
  // cut, run in a child process stopped after decomposition_time_limit seconds (> 0), the
  // cuts with at most half of it, the graph's a tenth (detail::voronoi_share).
  bool decompose = true;
  double decomposition_time_limit = 60;
  voronoi::VoronoiOptions graph;  // the Voronoi graph the decomposition cuts along
  double sharp_angle = 60;        // degrees (decompose::DecomposeOptions::sharp_angle)
  // Seconds after which meshing stops like a cancel, with a `time_limit` error (0: none).
  // Checked between and inside stages; the tetrahedral fallback's CGAL step is not
  // interrupted.
  double time_limit = 0;
  // Element order: 1 (8-node hexahedra) or 2 (20 nodes: mid-edge nodes on the CAD edge or
  // face they belong to, straight inside; checked at 27 Gauss points).
  int order = 1;
  void validate() const;  // throws std::invalid_argument naming the bad option
};

struct MeshStats {
  double size_used = 0;                      // the target size actually applied
  std::vector<core::LocalSize> local_sizes;  // the local sizes applied (each entity once)
  std::array<int, 3> intervals{};            // map: per block direction; sweep: {0, 0, layers}
  double seconds_meshing = 0;
  double seconds_smoothing = 0;
  double seconds_checking = 0;
  // Scaled Jacobian before and after smoothing (equal when smoothing is off).
  double min_sj_before_smoothing = 0, mean_sj_before_smoothing = 0;
  int sub_volumes = 0;
  // "map" (mapped block), "sweep" (one-to-one sweep), "multisweep" (prismatic), "revolve"
  // (solid of revolution), "midpoint" (convex polyhedron), "grid" (the fallback) or "tet-split"
  // (the old fallback, on request); sub-volumes of a decomposition or several solids: their
  // schemes joined by "+" ("map+sweep")
  std::string scheme;
  // Per sub-volume (SubVolume cell data 1, 2, ...): its scheme.
  std::vector<std::string> sub_volume_schemes;
  // Per sub-volume: "Vs" (swept between two faces of the solid, the paper's f_s volumes),
  // "Ve" (a block, or a sweep from or to a cut face); one entry "Vs"/"Ve" for one scheme.
  std::vector<std::string> sub_volume_types;
  // The grid mesher's features smaller than the size, absorbed into composite faces
  // (grid/composites.h): the largest deviation of the final mesh's boundary on them from the
  // real surface, model units (-1: nothing absorbed, or not the grid mesher).
  double absorbed_deviation = -1;
  // The fallback's mesh was computed beside the decomposition (MeshOptions::fallback_beside).
  bool fallback_beside = false;
};

struct MeshResult {
  core::HexMesh mesh;
  bool ok = false;                      // a valid mesh was produced
  quality::CheckReport check;           // validity and quality of `mesh`
  std::vector<double> scaled_jacobian;  // per hex, for writers and the GUI
  std::vector<io::NamedGroup> groups;   // per CAD face, edge and vertex (nodes, element faces)
  MeshStats stats;
  std::vector<core::Diagnostic> diagnostics;
  grid::SmallFeatures absorbed;  // the grid mesher's composites (empty otherwise)
};

// Every single-solid scheme name MeshOptions::schemes accepts, in the default order (then
// "grid", which is not in the default list: it is the fallback).
const std::vector<std::string>& scheme_names();

MeshResult generate_mesh(const occ::Solid& solid, const MeshOptions& options,
                         const core::Progress& progress = {});

}  // namespace vorohex::pipeline
