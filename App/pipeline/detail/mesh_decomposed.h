// The pipeline's path for a solid no single scheme meshes: its decomposition (plane cuts,
// then tangent-plane cuts where pieces have knife edges, then the Voronoi graph; in a child
// process, pipeline/detail/decompose_isolated.h), the sub-volumes meshed into one conforming
// mesh (mesh/mesh_sub_volumes.h) and put back onto the solid's own topology
// (smooth/restore_topology.h).
#pragma once

#include <string>
#include <vector>

#include "core/progress.h"
#include "core/size_field.h"
#include "occ/solid.h"
#include "pipeline/generate_mesh.h"

namespace vorohex::pipeline::detail {

// A solid no single scheme meshes: decomposed into sub-volumes (in a child process), those
// meshed into one conforming mesh, which is put back onto the solid's own topology. True
// when result.mesh holds it (its stats and a `decomposed` info set; not smoothed or
// checked); else false with `why_not` (a sentence fragment), or a `cancelled` error when the
// user stopped it.
bool mesh_decomposed(const occ::Solid& solid, const MeshOptions& options,
                     const core::SizeField& sizes, const core::Progress& progress,
                     MeshResult& result, std::string& why_not);

// Schemes of several sub-volumes or solids, each once, in one order (map, sweep, multisweep,
// revolve, midpoint, grid, tet-split): "map+sweep" whichever sub-volume comes first.
std::string joined_schemes(const std::vector<std::string>& schemes);

}  // namespace vorohex::pipeline::detail
