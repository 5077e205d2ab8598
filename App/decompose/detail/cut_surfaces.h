// The surfaces the plane cuts cut along (decompose/plane_cuts.h): the planes and cylinders of
// the faces at concave edges, and the planes the later tries add (around holes, across feet,
// along fillets' strips), with how each becomes a tool of OCCT's splitter.
// Internal to App/decompose (plane_cuts.cpp).
#pragma once

#include <string>
#include <vector>

#include "occ/solid.h"
#include "occ/split_solid.h"

namespace vorohex::decompose::detail {

struct Plane {
  core::Vec3 normal;                // unit
  double offset = 0;                // normal . x = offset
  core::FaceId face;                // the model face it extends (the first found)
  std::vector<core::EdgeId> edges;  // the concave edges it is taken at
  bool tangent = false;             // tangent to the cylinder of `face`, in its place
  bool around_hole = false;         // around the hole of `face` (detail/hole_planes.h)
  bool at_foot = false;             // across the foot of the tapered `face` (detail/foot_planes.h)
  bool beyond = false;           // beyond the wall a fillet `face` rounds (detail/fillet_strips.h)
  bool mitre = false;            // between two fillets' strips, `face` one of them
  bool corner = false;           // where a straight strip meets a rounded corner's
  std::vector<core::Vec3> quad;  // a mitre's corners: the tool is that quad, not the whole plane
};

// A cylinder to cut along, the model face it extends and the concave edges it is taken at.
struct Cylinder {
  occ::CutCylinder surface;
  core::FaceId face;
  std::vector<core::EdgeId> edges;
  bool at_foot = false;  // through the foot of the concave fillet `face` (not its extension)
  bool ring = false;     // beyond the wall of the round pocket whose floor `face` rounds
  bool corner = false;   // a sector round a rounded corner of fillets' strips (`face` its own)
};

// The same cylinder (axis line and radius within `tol`).
bool same_cylinder(const occ::CutCylinder& a, const occ::CutCylinder& b, double tol);

// Adds `pl` to `planes` unless it is there (same plane within tol: its edges join it); a
// bounded plane (a mitre's quad) is a tool of its own.
void add_plane(std::vector<Plane>& planes, Plane pl, double tol);

// The surfaces of the faces at concave edges: planes, and cylinders (a post of round
// section on a plate, a round boss); false (with why) when a concave edge has a face of
// another kind (no exact surface to cut along).
bool concave_surfaces(const occ::Solid& s, std::vector<Plane>& planes,
                      std::vector<Cylinder>& cylinders, std::string& why);

// Each cylinder a planar face touches tangently is replaced by the planes tangent to it at
// right angles to that face, on the sides where its concave edges are (a lug on a tube: the
// plane across the tube's top, above which the lug is a plain sweep). False when none is.
bool tangent_planes_instead(const occ::Solid& s, std::vector<Plane>& planes,
                            std::vector<Cylinder>& cylinders);

// Removes the planes whose normal lies along none of the part's axes (the normal of its
// largest planar face, of the largest planar face at right angles to that, and their cross
// product) and whose every concave edge another surface in `planes` or `cylinders` cuts along
// already: a gusset's sloped face between the two legs of an angle, whose plane extended cuts
// wedges out of both legs. True when any was removed.
bool drop_oblique_planes(const occ::Solid& s, std::vector<Plane>& planes,
                         const std::vector<Cylinder>& cylinders);

// Whether a piece has an edge where its two faces meet at an angle near zero (a knife)
// that is no such edge of the solid (a cut surface tangent to a face of the solid).
bool adds_knife_edges(const occ::Solid& solid, const std::vector<occ::Solid>& pieces);

// The plane's tool for the splitter: its quad where bounded, else a square on it covering the
// solid.
std::vector<core::Vec3> tool_of(const occ::Solid& s, const Plane& pl);

}  // namespace vorohex::decompose::detail
