// Decomposition of a solid into sweepable and mappable sub-volumes from its embedded
// Voronoi graph (paper §4): Voronoi edges are classified ([0] [1] [1s] [2] [3] [1e] [0e]
// [C]), the edges of interest and their end vertices are projected onto their governors
// (one point per governor face at a vertex, closing rectangles v, pi_a(v), pi_ab(v),
// pi_b(v)), the resulting quadrilaterals split a copy of the solid (the input is never
// modified), coplanar pieces are unified, and each sub-volume is typed Vs (holds an f_s
// face) or Ve and given a meshing scheme. A merge pass (paper §7) then unites adjacent
// sub-volumes whose union is sweepable. The rule table is in docs/decomposition.md.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "core/progress.h"
#include "decompose/detail/rules.h"
#include "occ/solid.h"
#include "voronoi/voronoi_graph.h"

namespace vorohex::decompose {

using core::Vec3;
using detail::EdgeType;
using model::EntityRef;

struct DecomposeOptions {
  // A [1] Voronoi edge whose two adjacent governor faces meet at an interior dihedral angle
  // below this is [1s] (projected onto both faces instead of their common edge). Degrees,
  // in (0, 180].
  double sharp_angle = 60;
  // Unite adjacent sub-volumes whose union is sweepable (the paper's §7 proposal).
  bool merge = true;
  // The meshers that judge the sub-volumes besides the mapped block, the one-to-one sweep
  // and midpoint subdivision: a prismatic sub-volume is a multisweep (many-to-one sweep with
  // submapped walls; mesh_sub_volumes meshes it beside blocks and sweeps), and a solid that
  // stays one sub-volume is revolved where it is a solid of revolution (meshed on its own
  // only). The mesh pipeline follows its own `schemes`.
  bool multisweep = true;
  bool revolve = true;
  // Geometric tolerance (coincident points, coplanarity, faces on faces), relative to the
  // bounding-box diagonal; (0, 0.01].
  double tolerance = 1e-6;
  // Decomposition quads whose planes differ by less than this (and 5 degrees) are moved
  // onto one plane before the split: the embedding places Voronoi elements to about
  // VoronoiOptions::delta, so nominally coplanar quads are slightly tilted. Relative to
  // the bounding-box diagonal; [0, 0.05].
  double plane_snap = 0.005;
  // Voronoi edge polylines are simplified to within this before their quads are built
  // (one quad per remaining segment and target): the embedding samples edges densely.
  // Relative to the bounding-box diagonal; [0, 0.05].
  double polyline_tolerance = 0.002;
  // Safety nets (reported as errors, never silent): more decomposition quads than this
  // times the model's face count, or an OCCT split running longer than split_time_limit
  // seconds (0: no limit), fails the decomposition instead of growing without bound.
  int max_quads_per_face = 40;
  double split_time_limit = 30;
  // Fail before the split where the vertex rules leave a gap open (error open_gap_stop,
  // naming the Voronoi vertex): the decomposition is partial then, and on HexMe none of the
  // 14 models with such a gap gave sub-volumes that all have a scheme, while their splits
  // took up to the split's limit. The mesh pipeline's choice (its fallback waits for the
  // decomposition); `vorohex decompose` shows the whole.
  bool stop_at_open_gap = false;
  // Empty if valid, else the reason.
  std::string validate() const;
};

// A Voronoi edge and what the decomposition does with it.
struct ClassifiedEdge {
  int element = -1;  // index in the VoronoiGraph
  EdgeType type = EdgeType::none;
  bool interest = false;
  std::vector<detail::Target> targets;  // what it is projected onto (empty: not projected)
};

// A Voronoi vertex with its vertex-table row and closing rectangles.
struct TreatedVertex {
  int element = -1;
  std::string row;  // e.g. "[2,2,C,C]"
  std::vector<detail::Rectangle> rectangles;
  std::vector<std::pair<EntityRef, EntityRef>> points;  // (governor face, entity projected on)
  std::vector<EntityRef> open;                          // governor faces left with a gap (reported)
};

// A generated quadrilateral before merging (3 points when two corners coincide).
struct DecompositionQuad {
  std::vector<Vec3> points;
  std::vector<bool> anchored;        // per point: on an edge governor (the plane snap keeps it)
  std::vector<EntityRef> supports;   // per point: the model face or edge it lies on (id 0: inside)
  int element = -1;                  // the generating Voronoi edge or vertex
  std::string kind;                  // "edge" or "rectangle"
  std::vector<EntityRef> governors;  // edge: the target's faces; rectangle: the two faces
  EntityRef target;                  // edge: the entity projected onto; rectangle: the shared edge
};

// A decomposition face as it bounds the final sub-volumes (quads merged where coplanar).
struct DecompositionFace {
  std::array<int, 2> sub_volumes{-1, -1};  // the sub-volumes on either side (-1: none)
  int num_edges = 0;
  double area = 0;
  // The smallest interior angle (degrees) of its sub-volumes at its edges: between it and
  // each neighbouring face, on either side (180 until measured by the final self-check).
  double min_angle = 180;
  Vec3 point{0, 0, 0};        // a point inside it
  std::vector<int> quads;     // the generating quads lying on it
  std::vector<int> elements;  // their Voronoi elements (sorted, unique)
};

// Virtual topology: every face of every sub-volume knows where it lies.
struct VirtualFace {
  int sub_volume = -1;
  core::FaceId face;            // the face in the sub-volume's solid
  core::FaceId original;        // the original face it lies on (invalid if none)
  int decomposition_face = -1;  // index in DecompositionResult::faces (or -1)
  int num_edges = 0;
  double area = 0;
};
// Every edge of every sub-volume: the original edge it lies on (a piece of it, or all of
// it), else the original face it lies in (a cut crossing that face), else neither (inside
// the solid, where decomposition faces meet).
struct VirtualEdge {
  int sub_volume = -1;
  core::EdgeId edge;           // the edge in the sub-volume's solid
  core::EdgeId original;       // the original edge it lies on (invalid if none)
  core::FaceId original_face;  // else the original face it lies in (invalid if none)
};
struct VirtualTopology {
  std::vector<VirtualFace> faces;
  std::vector<VirtualEdge> edges;  // filled once the sub-volumes are final
};

enum class SubVolumeType { vs, ve };
// midpoint: a convex cell for midpoint subdivision (Ve); it is meshed on its own only (its
// faces' subdivision is not the mapped grid a neighbour would put on them). multisweep: a
// prismatic sub-volume (many-to-one sweep); revolve: the one sub-volume of a solid of
// revolution (meshed on its own only).
enum class Scheme { sweep, map, midpoint, multisweep, revolve, none };
const char* sub_volume_type_name(SubVolumeType t);  // "Vs", "Ve"
// "sweep", "map", "midpoint", "multisweep", "revolve", "none"
const char* scheme_name(Scheme s);

// The scheme the mesh pipeline takes for `solid` whole, in its order (a mapped block, a
// sweep, a multisweep, a revolve, midpoint subdivision; the options say which of the
// multisweep and the revolve are allowed), or none; why in `reason`. Judged as the meshers
// judge, without meshing (a scheme that applies can still fail as it meshes).
// A sweep's source and target in `ends` where given.
Scheme whole_solid_scheme(const occ::Solid& solid, const DecomposeOptions& options,
                          std::string* reason,
                          std::pair<core::FaceId, core::FaceId>* ends = nullptr);

struct SubVolume {
  std::shared_ptr<const occ::Solid> solid;
  SubVolumeType type = SubVolumeType::ve;
  int fs_face = -1;  // the Voronoi f_s face it holds (Vs)
  Scheme scheme = Scheme::none;
  std::string reason;           // why this scheme (or why none)
  core::FaceId source, target;  // sweep source and target in `solid` (sweep)
  double volume = 0;
  int merged_from = 1;  // how many sub-volumes of the first split it unites
};

struct DecompositionStats {
  int edges_of_interest = 0;
  int projected_edges = 0;
  int vertices_treated = 0;
  int quads = 0;
  int decomposition_faces = 0;
  int sub_volumes_before_merge = 0;
  int sub_volumes = 0;
  double seconds = 0;
};

enum class DecompositionStatus { ok, partial, failed };

struct DecompositionResult {
  std::vector<ClassifiedEdge> edges;    // every Voronoi edge
  std::vector<TreatedVertex> vertices;  // every Voronoi vertex touching an edge of interest
  std::vector<DecompositionQuad> quads;
  std::vector<DecompositionFace> faces;
  std::vector<SubVolume> sub_volumes;
  VirtualTopology topology;
  DecompositionStatus status = DecompositionStatus::failed;
  std::vector<core::Diagnostic> diagnostics;
  DecompositionStats stats;
  bool ok() const { return status != DecompositionStatus::failed; }
};

// Only the first step: the type of every Voronoi edge (what the GUI colours the graph
// by). Empty when the graph or the options are unusable.
std::vector<ClassifiedEdge> classify_edges(const voronoi::VoronoiResult& voronoi,
                                           const DecomposeOptions& options = {});

// `voronoi` must be the graph of `solid` (its model gives the governors' relations).
// partial: some sub-volume has no scheme, some vertex gap stayed open, a Voronoi edge was
// unusable, or some decomposition face is not a quadrilateral between two sub-volumes
// (diagnostics say which); failed: invalid options, no model, an open gap with
// stop_at_open_gap, too many quads, OCCT could not split (or not in time), or the final self-check
// found the sub-volumes not closed, overlapping or not summing to the solid's volume (1e-9
// relative). `progress` gets stage "decompose" (fractions) and bounds the whole: the split and the
// merge pass get at most the time left before its deadline. Cancelled, the decomposition
// fails with error `cancelled` naming the step; past the deadline before the split has
// given sub-volumes, with error `time_limit` naming the step. Past it after, the merge pass
// stops (info merge_stopped) and the sub-volumes it has are checked (the self-checks run to
// their end) and returned.
DecompositionResult decompose(const occ::Solid& solid, const voronoi::VoronoiResult& voronoi,
                              const DecomposeOptions& options = {},
                              const core::Progress& progress = {});

// Why a decomposition is partial, in one line: the warnings that make it so, counted by
// kind ("2 sub-volumes have no scheme (no_scheme); 3 decomposition faces are not ...");
// empty for one that is not partial.
std::string partial_reason(const DecompositionResult& r);

// For callers that run decompose() in a child process (vorohex decompose, VoroHex.decompose):
// the seconds they wait past its time limit before killing the child where OCCT's split
// does not return (its deadline is only polled at OCCT's progress points): 10 %, at least
// 2 s; and the `time_limit` error such a kill gives.
double stop_grace(double time_limit);
core::Diagnostic not_stopped_error(double time_limit);

}  // namespace vorohex::decompose
