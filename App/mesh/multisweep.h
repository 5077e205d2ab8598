// Many-to-many sweeping of prismatic ("2.5-D") solids along a straight axis: every face is
// a cap perpendicular to the axis or a wall parallel to it (occ/prismatic.h), at any number
// of levels: stepped extrusions, plates with bosses, pockets and holes along the axis,
// flanged pipes, turned shafts with only cylinders and shoulders. The caps' outlines are
// overlaid in the base plane, the regions meshed once with conforming quads (face_set.h:
// mapped, submapped or general quads), and each slab between two levels is the extrusion
// of the regions inside it, so several sources at different levels sweep onto one target
// and walls with steps are meshed as submapped faces, with no decomposition. The result is
// independent of how the solid was modelled (edge order, seams, orientation): it depends
// only on its geometry. A sloped cap (occ/prismatic.h: a pyramidal pocket's floor, a hip
// roof) bends its level: the columns over it end on it, their layers spread between the
// levels as they lie over each node.
#pragma once

#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"
#include "core/mesh_domain.h"
#include "core/progress.h"
#include "core/size_field.h"

namespace vorohex::mesh {

struct MultisweepOptions {
  double size = 1.0;           // target edge length, model units (> 0)
  int max_intervals = 100000;  // per edge and per slab (> 0)
  int smoothing_passes = 30;   // of regions meshed by the general quad mesher (>= 0)
  // Counts some of the solid's edges must have (per edge id, entry 0 unused; 0 or missing:
  // free), e.g. where a neighbouring sub-volume has already placed its nodes: an edge at one
  // height fixes the regions' edges under it, an edge along the axis the layers of the
  // slabs it spans. Counts that cannot be met give intervals_infeasible.
  std::vector<int> edge_intervals;
  // Nodes some of the solid's open edges must have (per edge id, first to last vertex;
  // empty or missing: free), where a neighbour placed them: the regions' edges under an edge
  // at one height and the layers of the slabs an edge along the axis spans take them (a
  // vertex of the cross-section or a level that is not one of them: intervals_infeasible).
  std::vector<std::vector<core::Vec3>> edge_nodes;
  // Local sizes (null or uniform: `size` everywhere): the cross-section is graded where any
  // slab asks, each slab's layers follow its finest column. Not owned.
  const core::SizeField* size_field = nullptr;
  void validate() const;  // throws std::invalid_argument naming the bad field
};

struct MultisweepApplicability {
  bool ok = false;
  std::string reason;  // why not, naming the first face or edge that breaks the structure
  core::Vec3 axis = core::Vec3::UnitZ();
  int levels = 0, regions = 0;
};

MultisweepApplicability multisweep_applicable(const core::MeshDomain& solid);

struct MultisweepEstimate {
  int layers = 0;                    // along the axis, over all slabs
  std::size_t nodes = 0, hexes = 0;  // exactly what multisweep() produces (0 when refused)
};
// Builds the structure and meshes the regions (cheap next to the volume) to count exactly.
MultisweepEstimate multisweep_evaluate(const core::MeshDomain& solid,
                                       const MultisweepOptions& options);

struct MultisweepResult {
  core::HexMesh mesh;
  core::Vec3 axis = core::Vec3::UnitZ();
  int levels = 0, regions = 0, layers = 0;
  double region_min_quality = 0, region_mean_quality = 0;  // 2-D quad scaled Jacobian
  bool ok = false;
  std::vector<core::Diagnostic> diagnostics;
};

// Errors: not_applicable (with the reason), intervals_infeasible, quad_face_failed,
// too_many_intervals, inverted_elements, cancelled.
MultisweepResult multisweep(const core::MeshDomain& solid, const MultisweepOptions& options,
                            const core::Progress& progress = {});

}  // namespace vorohex::mesh
