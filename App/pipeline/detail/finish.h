// What every mesh the pipeline makes goes through before it is handed over: the global
// smoothing (unless the mesh's topology is broken, which moving nodes cannot mend), the
// named groups, second order if asked, and the validity check.
#pragma once

#include <string>
#include <vector>

#include "core/progress.h"
#include "core/size_field.h"
#include "occ/solid.h"
#include "pipeline/generate_mesh.h"

namespace vorohex::pipeline::detail {

// The sub-volume type of a solid meshed by one scheme: a sweep runs between two of its
// faces (Vs), a block or a midpoint cell is Ve, the fallbacks (grid, tet-split) are neither.
std::string type_of_scheme(const std::string& scheme);

// Smooths result.mesh (options.smoothing, graded by `sizes`) and checks it against `solid`:
// result.check, result.groups, result.ok and the stats' smoothing and checking figures. A
// mesh with open boundary edges or quads shared by more than two hexahedra is not smoothed,
// nor a tet split's mesh whose volume is off by several times what the check allows (info
// smoothing_skipped); the check names what is wrong. Cancelled: error `cancelled`.
void finish(MeshResult& result, const occ::Solid& solid, const MeshOptions& options,
            const core::Progress& progress, const core::SizeField& sizes);

// What made result's mesh: its diagnostics without its errors and what its smoothing and
// check said (those are said again of a mesh made from it and finished again).
std::vector<core::Diagnostic> diagnostics_of_making(const MeshResult& result);

// A structured mesh (not the fallbacks', nor several solids' where one is a fallback's)
// below kFlatPillowBar with hexahedra whose two
// boundary quads lie nearly flat across an edge (grid::flat_doublets: a fillet's tangent
// edge) gets a pillow layer under its whole boundary (grid::pillow_boundary), is finished
// again, and is replaced where that mesh is valid and its minimum scaled Jacobian at least
// kFlatPillowGain higher (warning `boundary_pillowed`, with both minima); else it stays
// (info `boundary_pillow_failed`). A block with its top edges filleted, mapped: 0.314 ->
// 0.500 (960 -> 1,592 hexahedra); at diagonal / 25, 0.209 -> 0.500.
void pillow_flat_doublets(MeshResult& result, const occ::Solid& solid, const MeshOptions& options,
                          const core::Progress& progress, const core::SizeField& sizes);

}  // namespace vorohex::pipeline::detail
