// The decomposition as the mesh pipeline uses it, for a solid that no single scheme meshes:
// exact cuts at its concave edges (decompose/plane_cuts.h), else the Voronoi graph and
// decomposition (with merging), in a child process with a time limit
// (core/isolated_call.h), since both can take minutes or much memory on complex parts
// (HexMe's i-series): the pipeline then falls back instead of waiting. What comes back is
// the sub-volumes glued at their common faces, when there are at least two and each has a
// scheme; otherwise why not.
#pragma once

#include <memory>
#include <string>

#include "core/progress.h"
#include "decompose/plane_cuts.h"
#include "occ/solid.h"
#include "pipeline/generate_mesh.h"

namespace vorohex::pipeline::detail {

struct IsolatedDecomposition {
  std::unique_ptr<occ::Solid> pieces;  // glued sub-volumes (null: none usable)
  std::unique_ptr<occ::Solid> afresh;  // plane cuts: the same split afresh, glued (or null;
                                       // decompose::PlaneCutResult::afresh)
  int before_merge = 0;                // sub-volumes of the first split
  std::string method;                  // "voronoi", or "plane cuts" (decompose/plane_cuts.h)
  std::string left_out;                // plane cuts: the surfaces left out ("the cylinder
                                       // of Face13, ..."; empty: none)
  std::string along;                   // plane cuts: the surfaces cut along ("the plane of
                                       // Face3, the cylinder of Face9 and 4 more")
  bool knife_edges = false;            // plane cuts: PlaneCutResult::knife_edges
  decompose::MergeHistory merges;      // plane cuts: PlaneCutResult::merges
  std::string cut_kind;                // plane cuts: decompose::cut_kind_text
  std::string why_not;                 // when pieces is null: a sentence fragment
  bool cancelled = false;              // stopped by `progress` (not by the time limit)
  double seconds = 0;
};

// Which decompositions to try. The exact cuts come first: on HexMe every model meshed as
// several sub-volumes was cut that way (i06, i10), and they fail within a second where a
// concave edge has no plane or cylinder to cut along, so the Voronoi decomposition keeps
// its time there.
enum class DecompositionMethods {
  plane_cuts_then_voronoi,  // the cuts (with at most half the time), else the Voronoi one
                            // (with at most a tenth)
  voronoi,                  // only the Voronoi decomposition (the pipeline's last try,
                            // when the cuts' sub-volumes did not mesh together)
  tangent_plane_cuts,       // only the cuts with tangent planes instead of the cylinders
                            // that planar faces touch (PlaneCutOptions::tangent_planes):
                            // where the cuts' pieces had knife edges and did not mesh
};

// The Voronoi decomposition's share of a decomposition time limit: at most a tenth (6 s of
// the default 60). Where its sub-volumes all have a scheme on HexMe (15 models,
// bench/results/hexme.md) it ends within 0.6 s; where it takes longer it fails (i02 after
// 38 s and i12 after 36 s with volume_mismatch, i07 and i23 at the split's limit), and the
// fallback waited for it (HexMe i12: 43 s after 13 s of plane cuts when it took what the
// cuts left, 30 s at half; i08: 27 s of plane cuts, then 15 s of the graph at a quarter,
// 51-65 s in all, over the 60 s).
inline double voronoi_share(double time_limit) {
  return 0.1 * time_limit;
}

// Uses options.graph, sharp_angle and decomposition_time_limit (seconds the child may
// take before it is stopped).
IsolatedDecomposition decompose_isolated(
    const occ::Solid& solid, const MeshOptions& options, const core::Progress& progress,
    DecompositionMethods methods = DecompositionMethods::plane_cuts_then_voronoi);

}  // namespace vorohex::pipeline::detail
