// The decomposition as the mesh pipeline uses it: Voronoi graph and decomposition (with
// merging) of a solid that no single scheme meshes, else exact plane cuts at its concave
// edges (decompose/plane_cuts.h), in a child process with a time limit
// (core/isolated_call.h), since both can take minutes or much memory on complex parts
// (HexMe's i-series): the pipeline then falls back instead of waiting. What comes back is
// the sub-volumes glued at their common faces, when there are at least two and each has a
// scheme; otherwise why not.
#pragma once

#include <memory>
#include <string>

#include "core/progress.h"
#include "occ/solid.h"
#include "pipeline/generate_mesh.h"

namespace vorohex::pipeline::detail {

struct IsolatedDecomposition {
  std::unique_ptr<occ::Solid> pieces;  // glued sub-volumes (null: none usable)
  int before_merge = 0;                // sub-volumes of the first split
  std::string method;                  // "voronoi", or "plane cuts" (decompose/plane_cuts.h)
  std::string why_not;                 // when pieces is null: a sentence fragment
  bool cancelled = false;              // stopped by `progress` (not by the time limit)
  double seconds = 0;
};

// Uses options.graph, sharp_angle and decomposition_time_limit (seconds the child may
// take before it is stopped). `plane_cuts_only`: no Voronoi decomposition (the pipeline's
// second try, when the Voronoi sub-volumes did not mesh together).
IsolatedDecomposition decompose_isolated(const occ::Solid& solid, const MeshOptions& options,
                                         const core::Progress& progress,
                                         bool plane_cuts_only = false);

}  // namespace vorohex::pipeline::detail
