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
  void validate() const;   // throws std::invalid_argument naming the bad field
};

// A surface the solid is cut along: the plane or the cylinder of a model face, extended
// through the solid from the concave edges it is taken at (why a cut is where it is).
struct CutSurface {
  bool cylinder = false;            // false: a plane
  core::FaceId face;                // the model face it extends
  std::vector<core::EdgeId> edges;  // the concave edges it is taken at
  bool used = true;                 // false: left out (OCCT's cut with it failed)
};

struct PlaneCutResult {
  // Each a block, a sweep or prismatic once glued to the others; when not ok but the solid
  // was cut: the pieces as cut, for inspection (vorohex decompose --plane-cuts).
  std::vector<occ::Solid> pieces;
  int planes = 0;     // distinct cut planes used
  int cylinders = 0;  // distinct cut cylinders used
  int pieces_before_merge = 0;
  // Every surface its concave edges give, planes first (none when it was not attempted);
  // one not `used` was left out because OCCT's cut along it with the others failed: its
  // concave edges are not cut at.
  std::vector<CutSurface> surfaces;
  bool ok = false;
  std::string why_not;  // when not ok: a sentence fragment
};

// Only solids whose concave edges all lie between planar or cylindrical faces are
// attempted; a cylinder is extended along its axis through the whole solid (the round post
// on a plate: the plate is cut around the post's circle and under it).
// The surfaces left out, as one list ("the plane of Face7, the cylinder of Face13"; empty
// when none).
std::string left_out_text(const PlaneCutResult& cut);
// "the plane of Face7 (at Edge12, Edge14)"; without the edges: "the plane of Face7".
std::string surface_text(const CutSurface& surface, bool with_edges = true);
// The surfaces used, without their edges, the first `at_most` named ("the plane of Face3,
// the cylinder of Face9 and 4 more").
std::string used_surfaces_text(const PlaneCutResult& cut, std::size_t at_most = 6);

PlaneCutResult cut_at_concave_edges(const occ::Solid& solid, const PlaneCutOptions& options = {},
                                    const core::Progress& progress = {});

}  // namespace vorohex::decompose
