// Decomposition by exact plane cuts at concave edges: the cut the Voronoi decomposition
// approximates at a concave model edge between two planar faces is the extension of one
// of those faces into the solid (the L's corner cut, the cut under a post standing on a
// plate). Computed exactly, with the whole plane through the solid (so that the pieces
// meet face to face, without T-junctions), then pieces whose union stays a block or a
// sweep once glued to its neighbours are merged again. The pipeline uses it when the
// Voronoi decomposition does not give sub-volumes every scheme accepts: its cuts are placed
// only as accurately as the graph's embedding, and OCCT's split of nearly coincident faces
// fails or leaves slivers on simple parts.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/progress.h"
#include "occ/solid.h"

namespace vorohex::decompose {

struct PlaneCutOptions {
  int max_planes = 16;     // more distinct cut surfaces than this: not attempted (>= 1)
  int max_pieces = 100;    // more pieces after cutting: not attempted (>= 2)
  double time_limit = 30;  // seconds for the whole (> 0); OCCT splits stop at it
  bool multisweep = true;  // pieces may be prismatic (multisweeps), not only blocks and sweeps
  bool revolve = false;    // pieces may be solids of revolution (the cuts at concave fillets' feet)
  bool merge = true;       // false: the pieces of the cut as they are (each with a scheme)
  // Each cylinder a planar face touches tangently replaced by planes tangent to it (see
  // CutSurface): where the cut with the cylinders leaves knife edges.
  bool tangent_planes = false;
  void validate() const;  // throws std::invalid_argument naming the bad field
};

// A surface the solid is cut along: the plane or the cylinder of a model face, extended
// through the solid from the concave edges it is taken at (why a cut is where it is).
// A cylinder that a planar model face touches tangently along a line (a lug as wide as the
// tube it stands on: its sides are tangent to the tube) can leave a piece with an edge of
// zero angle there (a knife), where no hexahedron is good. With
// PlaneCutOptions::tangent_planes each such cylinder is replaced by the plane tangent to it
// on the side of its concave edges, at right angles to that face (`tangent`). Only then: on
// a boss with a rounded end (its sides tangent to its end's cylinder) the cylinder's cut
// and the merging do better (HexMe i18).
struct CutSurface {
  bool cylinder = false;            // false: a plane
  bool tangent = false;             // a plane tangent to the cylinder of `face`, in its place
  core::FaceId face;                // the model face it extends
  std::vector<core::EdgeId> edges;  // the concave edges it is taken at
  bool used = true;                 // false: left out (OCCT's cut with it failed)
  // A plane parallel to the axis of the hole of `face`, about one and a half radii from it
  // (cut_as_the_mesher's third try: a cross hole, which has no concave edge).
  bool around_hole = false;
  // A plane across an axis at the foot of the tapered `face`, at `edges` where it meets a
  // wall (cut_as_the_mesher's fourth try: a block with chamfered top edges).
  bool at_foot = false;
  // A cylinder around a round pocket whose floor `face` rounds, as far beyond its wall as the
  // fillet's foot is inside it (the sixth try: the pocket's fillet on a ring of revolution).
  bool ring = false;
  // A plane as far beyond the wall that the concave fillet `face` rounds at a floor as its foot
  // on the floor is inside it (the fifth try: the strips fillets along floors lie on; the
  // plane across the foot is `at_foot`).
  bool beyond = false;
  // The plane between two such strips where their fillets meet at a corner (`face` one of
  // them, `edges` their mitre), cut only between the strips' planes.
  bool mitre = false;
  // The plane through a rounded corner's axis where a straight strip meets the corner's
  // (`face` the corner's fillet); the corner's cylinders are `at_foot` and `ring`.
  bool corner = false;
};

// The merge pass's unions, for the mesher to undo where one does not mesh (a sweep's layers
// fold in it): every piece the pass that gave the pieces started from or made (`solids`: the
// pieces as cut, then each union as made), the two each union was made of (indices into
// solids; -1 for a piece as cut), and each final piece's index in solids.
struct MergeHistory {
  std::vector<occ::Solid> solids;
  std::vector<std::array<int, 2>> from;
  std::vector<int> piece;
  bool empty() const { return solids.empty(); }
};

// Undoes the unions that parts `failed` of `glued` are: `pieces` (indices into h.solids,
// glued as `glued`) gets, for each, the two it was made of in its place. A part told by no
// piece's box, or by several, or that is a piece as cut, stays. Returns how many were undone.
int undo_unions(const MergeHistory& h, const occ::Solid& glued, const std::vector<int>& failed,
                std::vector<int>& pieces);

struct PlaneCutResult {
  // Each a block, a sweep or prismatic once glued to the others; when not ok but the solid
  // was cut: the pieces as cut, for inspection (vorohex decompose --plane-cuts).
  std::vector<occ::Solid> pieces;
  // When ok: the solid split afresh at the faces the pieces share only, the same pieces
  // without the traces of the cuts merged back (their edges and vertices, seams where a
  // cylinder was unified round) and without unifying the solid's own faces; empty where
  // that split does not give the same pieces, each with its scheme. The mesher meshes both
  // where the first meshes poorly and keeps the better.
  std::vector<occ::Solid> afresh;
  int planes = 0;     // distinct cut planes used
  int cylinders = 0;  // distinct cut cylinders used
  int pieces_before_merge = 0;
  // Octants of a ball (three fillets meeting at a corner) each parted into four blocks.
  int octants = 0;
  // Every surface its concave edges give, planes first (none when it was not attempted);
  // one not `used` was left out because OCCT's cut along it with the others failed: its
  // concave edges are not cut at.
  std::vector<CutSurface> surfaces;
  // Some piece has an edge where its faces meet at an angle near zero that is no such edge
  // of the solid (a knife), and a cylinder cut along is touched tangently by a planar face:
  // the cut with PlaneCutOptions::tangent_planes may do better.
  bool knife_edges = false;
  // The merging, run first without checking each merge's neighbours (the whole checked at the
  // end), did not end meshable and was run again from the cut with each merge's
  // neighbourhood checked.
  bool merges_checked_each = false;
  // When ok: the unions of the merge pass whose pieces these are (the first or the careful).
  MergeHistory merges;
  bool ok = false;
  std::string why_not;  // when not ok: a sentence fragment
};

// Only solids whose concave edges all lie between planar or cylindrical faces are
// attempted; a cylinder is extended along its axis through the whole solid (the round post
// on a plate: the plate is cut around the post's circle and under it).
// The surfaces left out, as one list ("the plane of Face7, the cylinder of Face13"; empty
// when none).
std::string left_out_text(const PlaneCutResult& cut);
// "the plane of Face7 (at Edge12, Edge14)"; without the edges: "the plane of Face7"; "the
// plane tangent to the cylinder of Face3" for a tangent plane, "the mitre plane of Face3".
std::string surface_text(const CutSurface& surface, bool with_edges = true);
// What the cut went along, for "Cut along ...": "the faces at its concave edges", "planes
// around its holes", or "the faces at its concave edges and planes around its holes".
std::string cut_kind_text(const PlaneCutResult& cut);
// The surfaces used, the first `at_most` named ("the plane of Face3, the cylinder of Face9
// and 4 more"; the planes around one hole once, "4 planes around the hole of Face5"; the
// fillets' strips once, "the strips of Face3 and Face7 (...), ended at 4 mitre planes"), with
// their concave edges when `with_edges`.
std::string used_surfaces_text(const PlaneCutResult& cut, std::size_t at_most = 6,
                               bool with_edges = false);

PlaneCutResult cut_at_concave_edges(const occ::Solid& solid, const PlaneCutOptions& options = {},
                                    const core::Progress& progress = {});

// The cut the mesher takes: cut_at_concave_edges, and where its pieces have knife edges and
// do not all have a scheme, the cut with the tangent planes instead (when that one is ok);
// else the cut at concave edges with planes around round holes too (a cross hole through a
// tube, a hole along a block beside a boss: detail/hole_planes.h), for each set of them until
// one is ok; else with planes across the feet of its tapered or rounded faces (a chamfered
// or filleted block: detail/foot_planes.h), each axis's set until one is ok; else along the
// strips of concave fillets on floors, ended at their mitres (a pocket whose floor edges are
// filleted: detail/fillet_strips.h); else with cylinders through the feet of concave round
// fillets and chamfers (a boss whose root is filleted: detail/foot_planes.h); all within what
// is left of options.time_limit. Not ok: the first cut's result.
PlaneCutResult cut_as_the_mesher(const occ::Solid& solid, const PlaneCutOptions& options,
                                 const core::Progress& progress = {});

}  // namespace vorohex::decompose
