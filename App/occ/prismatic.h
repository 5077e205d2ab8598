// The prismatic structure of a solid (a "2.5-D" part): every face is either a plane
// perpendicular to one axis (a cap) or a surface parallel to it (a wall: planes, cylinders,
// extrusions along the axis), and every edge is either a straight line along the axis or
// lies at one height. Such a solid is, between two consecutive heights of its vertices (its
// levels), a prism over a constant cross-section.
// A cap may also be sloped: a face whose normal stays within 60 degrees of the axis (a
// pyramid's side in a pocket or on a roof, a chamfer-like floor, drawn as a plane or a
// B-spline), with no seam, met once by every line along the axis over it. Its edges may
// climb (a ridge between two sloped caps, the slanted top of a wall); its vertices shared
// only with other sloped caps (an apex) are no level, and it belongs to the one level of
// its other vertices: over the regions it covers, that level lies on the face instead of at
// one height, and the slabs next to it thicken or thin there. Projected along the axis, the
// outlines of all caps, the horizontal edges and the vertices cut the base plane into regions (the
// arrangement, computed by OCCT's general fuse): each slab's cross-section is a union of
// regions, so meshing the regions once with conforming quads and extruding them slab by
// slab meshes the whole solid (a many-to-many sweep; Cubit's multisweep on such parts).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "occ/solid.h"

namespace vorohex::occ {

struct PrismaticStructure {
  bool ok = false;
  std::string reason;            // why not, naming the first face or edge that breaks the structure
  Vec3 axis = Vec3::UnitZ();     // unit; caps are perpendicular to it
  Vec3 origin = Vec3::Zero();    // a point of the base plane (height 0)
  std::vector<double> levels;    // heights (along axis, from origin) of the vertices, sorted
  std::vector<FaceId> caps;      // the solid's faces perpendicular to the axis
  std::vector<int> cap_level;    // per cap: its level index
  std::vector<bool> cap_up;      // per cap: its outward normal is +axis
  std::vector<bool> cap_sloped;  // per cap: a sloped cap (above), its level not flat
  // The regions as planar faces in the base plane, each oriented with normal +axis (wires
  // counter-clockwise about the axis); their edges and vertices are the arrangement's.
  std::unique_ptr<Solid> arrangement;
  // Per arrangement face id (entry 0 unused): the caps (indices into `caps`) covering it.
  std::vector<std::vector<int>> covering_caps;
  // Per arrangement face and slab (slab i between levels i and i + 1): inside the solid.
  // inside[face][slab]; derived from the caps crossed below (their parity), which is exact.
  std::vector<std::vector<bool>> inside;
  double height(const Vec3& p) const { return (p - origin).dot(axis); }
};

// Options: `axis` forces a direction (zero: try the directions of the solid's planar
// faces, cylinders and extrusions, and keep the one whose arrangement has the fewest
// regions, then levels). Never throws for geometry it cannot handle: ok false with reason.
// Works on any MeshDomain (the solid's own topology and geometry queries): the arrangement
// is built from the caps' edges as curves (lines, circles, or curves through samples).
PrismaticStructure prismatic_structure(const core::MeshDomain& solid,
                                       const Vec3& axis = Vec3::Zero());

// The area of the solid's planar faces across unit `axis` (planes, and B-splines that are
// flat): the caps of a sweep along it, how much the solid looks swept that way.
double area_across(const core::MeshDomain& solid, const Vec3& axis);

// Where an edge of the solid lies in the structure: an edge at one height or on a sloped cap
// over arrangement edges (their ids; their counts sum to the edge's), or an edge along the axis
// over slabs (their indices; their layers sum to its count). Neither (empty) for a degenerated edge
// or one that is not part of the structure.
struct EdgeInStructure {
  std::vector<int> arrangement_edges;
  std::vector<int> slabs;
};
EdgeInStructure edge_in_structure(const core::MeshDomain& solid, const PrismaticStructure& s,
                                  EdgeId e);

}  // namespace vorohex::occ
