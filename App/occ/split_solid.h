// Splitting a solid by decomposition faces (BOPAlgo splitter), and the few OCCT operations
// the decomposition stage needs on the pieces. The input solid is never modified: the
// pieces are new solids whose coplanar faces and collinear edges are unified.
#pragma once

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "occ/solid.h"

namespace vorohex::core {
class IsolatedServer;
}

namespace vorohex::occ {

struct SplitResult {
  std::vector<Solid> pieces;
  std::vector<core::Diagnostic> diagnostics;
  int dropped_internal_faces = 0;  // tool faces that ended inside a piece (removed)
  bool timed_out = false;          // stopped at `time_limit` (then not ok)
  bool ok = false;
};

// Splits `solid` by tool faces, each a closed polygon of 3 or 4 points (planar when its
// points are within `tolerance`, else a ruled surface between its first and last sides).
// Degenerate tools (area below tolerance^2) are ignored. `tolerance`: model units.
// `time_limit` (seconds, <= 0: none) stops OCCT's boolean through its progress break, so
// that tools OCCT cannot intersect in reasonable time give a diagnostic, not a hang.
SplitResult split_solid(const Solid& solid, const std::vector<std::vector<Vec3>>& tools,
                        double tolerance, double time_limit = 0);

// A cylinder to cut along: a point on its axis, the unit axis direction, the radius, and
// the axial range [from, to] measured from `origin` (the tool is the full round face).
struct CutCylinder {
  Vec3 origin{0, 0, 0};
  Vec3 axis{0, 0, 1};
  Vec3 seam{1, 0, 0};  // where the round face's seam lies (the model face's, so they agree)
  double radius = 0;
  double from = 0, to = 0;
  // The turn it spans from `seam` about `axis` (radians, right-handed): a sector where less
  // than a whole turn (the corner of a strip round a pocket's rounded corner).
  double angle = 2 * M_PI;
};

// The same with cylinders among the tools (curved faces at concave edges extended).
SplitResult split_solid(const Solid& solid, const std::vector<std::vector<Vec3>>& tools,
                        const std::vector<CutCylinder>& cylinders, double tolerance,
                        double time_limit = 0);

// `solid` split only at the faces the glued pieces of a split of it share (`glued`, their
// union: occ::glue_solids), without unifying: its own faces stay as they are except where
// those faces end on them. The pieces of a cut merged back leave the traces of the cuts
// they merged across (edges, vertices; a cylinder unified round into a closed face has its
// seam where two pieces met); split afresh at the common faces only, none is left.
SplitResult split_at_interfaces(const Solid& solid, const Solid& glued, double tolerance,
                                double time_limit = 0);

// The cylinder a face lies on (radius, axis through `origin`), if it is cylindrical.
bool face_cylinder(const Solid& solid, FaceId f, CutCylinder* cylinder);

// Whether every shell of the solid is closed (each edge bounds two of its faces with
// opposite orientations).
bool is_closed(const Solid& solid);

// A point strictly inside a face (from its triangulation), its outward normal there, its
// area and number of boundary edges (all wires).
struct FaceSample {
  FaceId face;
  Vec3 point{0, 0, 0};
  Vec3 normal{0, 0, 0};
  double area = 0;
  int num_edges = 0;
  int num_wires = 0;
};
std::vector<FaceSample> sample_faces(const Solid& solid);

// The union of two solids as one solid with unified faces, or null if it is not one solid.
// `time_limit` (seconds, > 0): the unification, which takes no progress indicator and can
// run without end, runs in a child process stopped at the limit (then null); 0: in this one.
// `split_faces_if_unification_fails`: where OCCT's unification throws (also without
// concatenating B-splines and without merging edges), the union keeps its faces split
// instead of being null (the plane cuts' merging: HexMe i14's tube, i18).
std::unique_ptr<Solid> fuse_solids(const Solid& a, const Solid& b, double time_limit = 0,
                                   bool split_faces_if_unification_fails = false);

// Unions made one after another (the plane cuts' merges), each as fuse_solids with a time
// limit, the unifications all in one child process kept for them (core::IsolatedServer)
// instead of a child forked per union: HexMe i22's 76 merges 5.2 -> 1.5 s.
class Fuser {
 public:
  Fuser();
  ~Fuser();
  Fuser(const Fuser&) = delete;
  Fuser& operator=(const Fuser&) = delete;
  std::unique_ptr<Solid> fuse(const Solid& a, const Solid& b, double time_limit,
                              bool split_faces_if_unification_fails = false);
  int children() const;  // child processes forked so far (one, or more after a stop)

 private:
  std::unique_ptr<core::IsolatedServer> server_;
};

// The difference a - b as one solid with unified faces, or null if it is not one solid.
std::unique_ptr<Solid> cut_solids(const Solid& a, const Solid& b);

// Volume of the common part of two solids (0 when disjoint or touching).
double common_volume(const Solid& a, const Solid& b);

// Writes the solids as one compound in a BREP file. False with `error` on failure.
bool write_compound_brep(const std::vector<const Solid*>& solids, const std::string& path,
                         std::string* error);

// The solids as one compound in BREP text (empty on an OCCT failure).
std::string compound_brep_string(const std::vector<const Solid*>& solids);

// The solids of a compound in BREP text, in its order, each on its own (not glued); none
// on an OCCT failure.
std::vector<Solid> solids_from_brep_string(const std::string& brep);

}  // namespace vorohex::occ
