// One-to-one sweeping: a solid with a source face (planar or curved, with holes), a target
// face, and linking faces that each have one wire of four sides (one edge on the source, a
// chain of edges on the target that meet at side vertices, where the chain turns by less
// than 30 degrees: a neighbour's vertex imprinted there, and two linking sides, each an
// edge or such a chain: mesh/detail/sweep_topology.h; the target may have an apex inside, a drill
// point's cone, reached along the axis). The source is meshed by quad_face, the target by the same
// topology mapped (least-squares affine map of the boundary loops, projected), the linking faces by
// transfinite interpolation (projected when curved), and the inner layers by the blend of the
// source- and target-based least-squares affine maps onto each layer's boundary (tolerates twist
// and taper).
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"
#include "core/mesh_domain.h"
#include "core/progress.h"
#include "core/size_field.h"

namespace vorohex::mesh {

struct SweepOptions {
  double size = 1.0;           // target edge length, model units (> 0)
  int max_intervals = 100000;  // per edge and for the layers; more is refused (> 0)
  int smoothing_passes = 30;   // of the source face mesh (>= 0)
  // Given intervals per edge id (entry 0 unused), e.g. from assign_intervals, instead of
  // the size: every linking edge the same count (the layers), each source edge the count
  // of the target edge across its linking face, each source loop even (at least 4, or 6
  // with holes); otherwise an error. With given intervals a source of one loop of four
  // edges whose opposite counts agree is meshed by transfinite interpolation, and so is
  // the target: a neighbour meshing the same face as a mapped face gets the same nodes.
  std::vector<int> edge_intervals;
  // Face ids not to take as the source while another source/target pair exists (as for
  // sweep_structure, so that both choose the same pair).
  std::vector<int> avoid_sources;
  // Local sizes (null or uniform: `size` everywhere): edge counts and node spacing follow
  // them, and the layers take the finest count any linking edge asks for. Not owned.
  const core::SizeField* size_field = nullptr;
  // Per edge id: nodes a neighbouring sub-volume already placed on it (first to last
  // vertex), taken instead of the edge's own spacing when their number fits its count.
  std::vector<std::vector<core::Vec3>> edge_nodes;
  // The target's inner nodes (a source meshed freely) where the line through each source
  // node's affine image along the sweep's axis (from the source's boundary centre to the
  // target's) meets the target, not at the point of the target nearest that image. Tried
  // where the layers fold: a cross hole's piece of a tube's wall, swept from the outer
  // cylinder to the inner, folds where the nearest points pull the nodes around the hole
  // sideways.
  bool target_along_axis = false;
  // The inner nodes of every layer, and of the target where the source is meshed freely,
  // as the layer below's deformed to the layer's boundary (mean value weights, step by step:
  // mesh/detail/sweep_layers.h), not by affine maps. Tried where the layers fold both ways
  // above: a countersunk hole's slab, swept from the small hole's plane to the large one's,
  // folds where the affine images of the nodes by the small hole land in the large one.
  bool smooth_layers = false;
  // The source's quads as a neighbour meshed that face (corner points, either orientation):
  // taken instead of meshing the source, where every node of its boundary is one of the
  // sweep's own boundary nodes (else the source is meshed as usual). A multisweep and a sweep
  // sharing a face mesh it alike this way (mesh_sub_volumes: the multisweep first).
  std::vector<std::array<core::Vec3, 4>> source_quads;
  // The target's quads as a neighbour meshed that face (corner points): the target's inner
  // nodes are put on theirs, each mapped node on the nearest, one to one (else an error,
  // `target_mismatch`). A ring of sweeps meeting at faces meshed freely (the strips around a
  // pocket's floor fillets, ended by mitre planes at its corners): the last one's target is
  // the first one's source, all of them the same quads carried round.
  std::vector<std::array<core::Vec3, 4>> target_quads;
  // A sub-volume glued to its neighbours (as sweep_applicable's `imprinted`).
  bool imprinted = false;
  void validate() const;  // throws std::invalid_argument naming the bad field
};

struct SweepApplicability {
  bool ok = false;
  std::string reason;           // why not, naming the entities
  core::FaceId source, target;  // the chosen pair when ok
};

// Finds a source/target pair: two faces sharing no vertex such that every other face is a
// four-sided linking face joining their loops. Among several pairs it prefers the shortest
// linking edges (fewest layers), then the largest source face.
// `imprinted`: a sub-volume glued to its neighbours, whose linking sides may then be chains of
// edges and stacks of faces where they imprinted theirs (mesh/detail/sweep_topology.h).
SweepApplicability sweep_applicable(const core::MeshDomain& solid, bool imprinted = false);

// The chosen sweep's structure (what an interval assignment must respect): empty when
// sweep_applicable refuses.
struct SweepStructure {
  core::FaceId source, target;
  // Per source loop, per edge in loop order: the source edge and the target edges across
  // its linking face (one, or a chain meeting at side vertices: their intervals sum to the
  // source edge's).
  std::vector<std::vector<std::pair<core::EdgeId, std::vector<core::EdgeId>>>> loops;
  // Every linking side: one edge, or a chain meeting at side vertices (a neighbour's
  // vertices imprinted there); each sums to the layer count.
  std::vector<std::vector<core::EdgeId>> linking;
  // Per edge between two faces of a stack of linking faces (one edge or a chain): the source
  // edge below it (their intervals sum to its), and the linking edges below it on either side
  // (theirs sum to the same: it lies on one layer).
  struct Level {
    core::EdgeId source;
    std::vector<core::EdgeId> across, below0, below1;
  };
  std::vector<Level> levels;
};
// `avoid_sources`: face ids not to take as the source while another pair exists (faces
// shared with a neighbour: their mesh is then the projection of the far end's).
SweepStructure sweep_structure(const core::MeshDomain& solid,
                               const std::vector<int>& avoid_sources = {}, bool imprinted = false);

struct SweepEstimate {
  int layers = 0;
  std::size_t nodes = 0, hexes = 0;  // exactly what sweep() produces (0 when refused)
};
// Plans intervals and meshes the source face (cheap next to the volume) to count exactly.
SweepEstimate sweep_evaluate(const core::MeshDomain& solid, const SweepOptions& options);

struct SweepResult {
  core::HexMesh mesh;
  core::FaceId source, target;
  int layers = 0;
  double source_min_quality = 0, source_mean_quality = 0;  // 2-D quad scaled Jacobian
  // Hexes with a non-positive corner Jacobian (the layers fold: not ok, error
  // inverted_elements); the folded mesh is kept, for a caller that untangles it.
  std::size_t folded = 0;
  bool ok = false;
  std::vector<core::Diagnostic> diagnostics;
};

SweepResult sweep(const core::MeshDomain& solid, const SweepOptions& options,
                  const core::Progress& progress = {});

// After a caller untangled a folded sweep's mesh (smooth::untangle_folded): ok, the fold
// said as a warning (sweep_untangled) instead of the error.
void accept_untangled(SweepResult& r);

}  // namespace vorohex::mesh
