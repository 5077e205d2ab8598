// Global smoothing and untangling of an all-hex mesh with its nodes kept on the CAD.
//
// Model-vertex nodes are fixed, edge nodes slide along their CAD curve, face nodes slide on
// their CAD surface (tangent step, then projection), interior nodes are free. Three phases:
//  1. Laplacian: each node moves towards the mean of its smoothing neighbours.
//  2. Untangling: nodes of inverted hexes (and of hexes flat up to rounding, scaled
//     Jacobian <= 1e-6) descend a regularised mean-ratio objective that stays finite for
//     inverted corners (Escobar et al.'s modified determinant). A face node whose step
//     would leave its face (held at the face's boundary) may cross onto the adjacent face
//     nearest to the step's target; one lying on its face's boundary that no move on its
//     face untangles tries the moves of a node on the adjacent face; either is classified
//     on the new face from then on. An edge node that no move along its edge untangles
//     may leave the edge for one of its faces (warning edge_nodes_released).
//  3. Optimisation: nodes of hexes below the quality target descend the same objective.
//     Where hexes are still inverted after it and the max-min phase, untangling and
//     optimisation run again (at most three rounds, while the inverted count falls).
// Every move is accepted only when no incident hex's scaled Jacobian falls below
// min(its previous value, floor), floor = max(quality_target, minimum of the input), so the
// minimum never decreases and no valid hex is ever inverted.
#pragma once

#include <cstddef>
#include <vector>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"
#include "core/progress.h"
#include "core/size_field.h"
#include "occ/solid.h"

namespace vorohex::smooth {

struct SmoothOptions {
  // Sweeps of the Laplacian phase over all movable nodes (>= 0; 0 skips the phase). The
  // phase stops earlier once no node moves more than `tolerance`.
  int laplacian_iterations = 20;
  // Passes of untangling and of worst-element optimisation (>= 0; 0 skips both).
  int optimisation_passes = 10;
  // Scaled Jacobian in (0, 1]: hexes below it are optimised in phase 3, and no move may
  // push a hex below min(its previous value, max(quality_target, input minimum)).
  double quality_target = 0.5;
  // Fraction of the Laplacian step taken, in (0, 1].
  double relaxation = 0.7;
  // A node moving less than this, relative to its mean incident edge length, counts as
  // converged (>= 0).
  double tolerance = 1e-4;
  // The Laplacian moves only nodes of which some incident hex has a scaled Jacobian below
  // this, in (0, 1] (1 = every node). Nodes whose hexes are all nearly perfect are left
  // alone: moving them gains nothing and costs most of the time on large good meshes.
  double active_below = 0.95;
  // Local sizes (null or uniform: none): the Laplacian weighs each neighbour by the inverse
  // of the size between them, so that it keeps a graded mesh graded. Not owned.
  const core::SizeField* size_field = nullptr;
  // Per node (empty: none): nodes kept where they are, such as those on a face another
  // mesh shares (a sub-volume untangled before its neighbours are joined to it).
  std::vector<char> fixed;
  void validate() const;  // throws std::invalid_argument naming the bad field
};

enum class SmoothStatus {
  ok,               // no inverted hex remains
  inverted_remain,  // some hexes could not be untangled (reported as an error diagnostic)
  cancelled,        // stopped by the progress object; the mesh is valid as far as it got
};

const char* status_name(SmoothStatus s);

struct SmoothResult {
  SmoothStatus status = SmoothStatus::ok;
  // Verdict scaled Jacobian before and after (hexes with value <= 0 count as inverted).
  double min_before = 0, mean_before = 0, min_after = 0, mean_after = 0;
  std::size_t inverted_before = 0, inverted_after = 0;
  std::size_t untangled = 0;            // hexes inverted in the input and valid in the output
  std::size_t fixed_nodes = 0;          // vertex nodes and nodes with an unknown/invalid entity
  std::size_t laplacian_moves = 0;      // accepted Laplacian node moves
  std::size_t optimisation_moves = 0;   // accepted untangling/optimisation steps
  std::size_t edge_nodes_released = 0;  // edge nodes moved onto a face to untangle
  int laplacian_sweeps = 0;             // Laplacian sweeps actually run
  double seconds = 0, seconds_laplacian = 0, seconds_optimisation = 0;
  std::vector<core::Diagnostic> diagnostics;
  bool ok() const { return status == SmoothStatus::ok; }
};

// Smooths `mesh` in place. Node classes must refer to entities of `solid` (1-based
// MapShapes ids); nodes with an id out of range are kept fixed and reported.
SmoothResult smooth_mesh(core::HexMesh& mesh, const occ::Solid& solid, const SmoothOptions& options,
                         const core::Progress& progress = {});

// A scheme's mesh with folded hexes (a sweep whose layers fold under the shift of a hole or
// a strong change of shape): smoothed and untangled as above (default options with the
// scheme's local sizes, `fixed` nodes kept). True when no hex is left inverted and the minimum
// scaled Jacobian reaches `min_quality` (below it, the next scheme or the fallback usually does
// better: a plate with a hole drilled at 30 degrees, swept by affine layers, untangled to 0.04,
// its grid mesh has 0.43); the nodes are moved either way.
bool untangle_folded(core::HexMesh& mesh, const occ::Solid& solid, const std::vector<char>& fixed,
                     const core::SizeField* size_field, const core::Progress& progress = {},
                     double min_quality = 0.3);

}  // namespace vorohex::smooth
