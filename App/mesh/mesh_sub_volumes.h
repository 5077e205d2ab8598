// Meshing several sub-volumes into one conforming mesh (paper §5.1): the sub-volumes are
// glued at their common faces (occ::glue_solids), each is given its scheme (a mapped block,
// else a one-to-one sweep, else a multisweep of a prismatic part), one interval assignment
// over every curve of all of them makes the counts agree where they meet, each sub-volume is
// meshed with those counts (in parallel), and the meshes are joined with nodes on common
// entities merged. Faces two sub-volumes share are meshed as mapped faces by both (the same
// transfinite nodes from the same edge nodes); a sweep's source of four sides is a mapped
// grid for that reason. Multisweeps are meshed first, one after the other, each meeting the
// counts of the ones before it on the edges they share, and their counts are fixed in the
// assignment of the others; the other shared edges' nodes are then placed once, on the glued
// sub-volumes, for all parts alike. A sweep whose source or target a multisweep meshed takes
// its quads there (paired by connectivity with its own lattice where that is mapped or
// submapped). Where a multisweep's face mesh still differs from its neighbour's (a shared
// cap a block maps), nothing is merged there and the validity check names the face. A
// sub-volume none of these takes
// may be a solid of revolution (a boss with its filleted root, cut out of its plate along
// the fillet's foot): revolved first, its circles all in one count (a multiple of 4), its
// sectors starting at the vertex of a circle it shares, its shared seams in their assigned
// counts; its neighbours take its nodes there.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"
#include "core/progress.h"
#include "core/size_field.h"
#include "occ/solid.h"

namespace vorohex::mesh {

struct SubVolumeMeshOptions {
  double size = 1.0;                 // target edge length, model units (> 0)
  int max_intervals = 100000;        // per curve (>= 1)
  int smoothing_passes = 30;         // of unstructured sweep sources (>= 0)
  double interval_time_limit = 20;   // seconds for the integer program (> 0)
  std::size_t max_hexes = 50000000;  // more is refused before meshing (>= 1)
  int threads = 0;                   // sub-volumes meshed at once (0: the machine's cores)
  bool multisweep = true;            // a sub-volume may be a multisweep (else blocks, sweeps)
  bool revolve = true;  // a sub-volume none of those takes may be a solid of revolution
  // Local sizes (null or uniform: `size` everywhere): the interval assignment's targets and
  // every piece's edge nodes and sweep sources follow them. Not owned.
  const core::SizeField* size_field = nullptr;
  void validate() const;  // throws std::invalid_argument naming the bad field
};

struct SubVolumeMeshStats {
  std::vector<std::string> schemes;  // per sub-volume: "map", "sweep" or "multisweep"
  // Per sub-volume: "Vs" when swept between two faces of the whole (not shared with a
  // neighbour: the paper's volumes around an f_s face), else "Ve" (blocks, and sweeps from
  // or to a cut face; multisweeps that share a face).
  std::vector<std::string> types;
  int curves = 0;  // curves in the interval assignment
  int constraints = 0;
  double interval_deviation = 0;  // the assignment's objective (see IntervalResult)
  std::size_t nodes_merged = 0;   // sub-volume nodes that became a common node
  double seconds_intervals = 0, seconds_meshing = 0;
};

struct SubVolumeMeshResult {
  core::HexMesh mesh;  // classified on the entities of `pieces`; cell data: sub-volume 1..n
  bool ok = false;
  std::vector<core::Diagnostic> diagnostics;
  SubVolumeMeshStats stats;
  // When not ok: the sub-volumes (0-based) whose own meshing failed (not those left unmeshed
  // because one they wait on failed).
  std::vector<int> failed;
};

// `pieces`: glued sub-volumes (Solid::num_solids() parts). Errors: no_scheme (a sub-volume
// neither a block, a sweep nor prismatic, named), intervals_infeasible, too_many_hexes, cancelled,
// and the schemes' own errors prefixed with the sub-volume.
SubVolumeMeshResult mesh_sub_volumes(const occ::Solid& pieces, const SubVolumeMeshOptions& options,
                                     const core::Progress& progress = {});

// The scheme mesh_sub_volumes gives each sub-volume of `pieces` ("map", "sweep", "multisweep"
// or, with `revolve`, "revolve"; empty
// for one that has none), without meshing: what a decomposition's merge pass asks of a
// union once glued to its neighbours. `why_not` names the first sub-volume without one.
struct SubVolumePlan {
  bool ok = false;  // every sub-volume has a scheme
  std::vector<std::string> schemes;
  std::vector<std::string> reasons;  // per sub-volume: why it has none (empty when it has one)
  std::string why_not;
};
// `imprinted`: a sweep's linking sides may be chains of edges and stacks of faces where
// neighbours imprinted theirs (mesh/sweep.h), where no sweep without them is found; meshing
// allows them (it takes the sweeps without them first, so a plan made without them holds).
SubVolumePlan plan_sub_volumes(const occ::Solid& pieces, bool multisweep = true,
                               bool revolve = false, bool imprinted = false);

}  // namespace vorohex::mesh
