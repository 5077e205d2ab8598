// Planes across an axis at the foot of a tapered face: where a chamfer along a block's top
// edges, or a countersink's cone, meets a wall (a face parallel to the axis) along an edge at
// one height. A block with its top edges chamfered is convex and has no concave edge, so
// the cuts at concave edges never touch it, and no one scheme takes it well (the midpoint
// subdivision: min scaled Jacobian 0.15); cut at the chamfers' foot it is a block and a
// tapered slab swept from its wide face to its narrow one, what a Cubit user webcuts. A
// rounded edge's fillet (a cylinder across the axis or a torus about it, bulging out of the
// solid) has its foot where it meets a wall tangentially: a block with its top edges
// filleted is a block and a slab whose sides the fillets are.
// Internal to App/decompose (the plane cuts' fourth try, docs/decomposition.md).
#pragma once

#include <vector>

#include "occ/solid.h"
#include "occ/split_solid.h"

namespace vorohex::decompose::detail {

// The plane normal . x = offset through the foot of tapered model face `face`, at `edges`.
struct FootPlane {
  core::Vec3 normal;  // unit, along the axis
  double offset = 0;
  core::FaceId face;
  std::vector<core::EdgeId> edges;
  // At the foot of a concave fillet on a wall (an L bracket's inner edge rounded): the plane
  // through the fillet's axis and its foot, across the wall.
  bool concave = false;
};

// Per axis (the directions of the solid's planar faces and cylinders): the planes at the
// feet of the faces tapered to it (planar faces neither along nor across it, cones about
// it) where they meet a wall or a cap, and of its fillets (convex, or concave: `concave`)
// where they meet a wall, along an edge at one height strictly inside the solid's extent
// along the axis; axes with none are left out.
struct FootPlaneSet {
  core::Vec3 axis;  // unit
  std::vector<FootPlane> planes;
  double cap_area = 0;  // of the planar faces across the axis
};
// The axes whose planar faces across them have the most area first (the axis a user would
// sweep along: a chamfered block's z, not its chamfers' normals).
std::vector<FootPlaneSet> foot_plane_sets(const occ::Solid& solid);

// The cylinder through the foot of a concave round fillet or a chamfer on its floor: a torus
// or a cone about an axis (a boss's root filleted or chamfered) that meets a planar face across
// that axis along a whole circle, tangentially or at a concave edge. Cut along the coaxial cylinder
// through that circle, across the floor at a right angle, the boss and its fillet come out of the
// plate as a solid of revolution, and the plate keeps a round hole: no knife edge (a cut along the
// floor would leave one where the fillet meets it tangentially). At a round pocket's floor, where
// the fillet also meets the pocket's wall, a second cylinder beyond the wall. The cylinders' seams
// pass through the circle's vertex, so that the circles the pieces share start where the cut's own
// circles do.
struct FootCylinder {
  occ::CutCylinder surface;  // along the solid's whole extent on its axis
  core::FaceId face;         // the fillet
  core::EdgeId edge;         // its foot
  // A cylinder beyond a round pocket's wall, as far from it as the foot on the floor, which
  // leaves the pocket's fillet or chamfer on a ring of revolution (the foot's face and edge).
  bool ring = false;
};
std::vector<FootCylinder> foot_cylinders(const occ::Solid& solid);

// Shared with the cuts at concave edges (plane_cuts.cpp):
// How faces f and g meet at point m of their common edge (tangent t there): the direction
// from the edge into f, across it, against g's outward normal. Above sin(1 degree) the edge
// is concave, below minus that convex, between them smooth.
double turn_across(const occ::Solid& s, const core::Vec3& m, const core::Vec3& t, core::FaceId f,
                   core::FaceId g);
// c.from and c.to set so that the cylinder runs along the solid's whole extent on its axis
// (the heights of its bounding box's corners, a tenth of the diagonal beyond).
void along_the_solid(const occ::Solid& s, occ::CutCylinder& c);

}  // namespace vorohex::decompose::detail
