// The revolution structure of a solid (a turned part): every face is a surface of
// revolution about one axis (planes perpendicular to it, coaxial cylinders, cones, tori,
// spheres centred on it, surfaces of revolution) and every edge a circle about the axis or
// a meridian curve (a seam). Such a solid is its meridian section turned by a full turn: the
// section is built from the faces' traces in a half-plane through the axis (read through
// core::MeshDomain: surface and curve kinds, parallels, projections; no boolean with the
// solid), checked against the volume (Pappus), meshed with quads and revolved. Where the section
// lies along the axis, a coaxial core of radius core_radius is cut out of it (to be swept along the
// axis from an O-grid disc, so that no hexahedron degenerates on the axis); the section's remaining
// faces are given here.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "occ/solid.h"

namespace vorohex::occ {

struct RevolutionCore {
  double z0 = 0, z1 = 0;  // the heights (along the axis) where the section lies on the axis
  FaceId bottom, top;     // the solid's planar faces the core ends on
};

struct RevolutionStructure {
  bool ok = false;
  std::string reason;           // why not, naming the face or edge
  Vec3 origin = Vec3::Zero();   // a point of the axis
  Vec3 axis = Vec3::UnitZ();    // unit
  Vec3 radial = Vec3::UnitX();  // unit, across the axis: the section's half-plane direction
  double max_radius = 0;        // of the solid
  // The section without the cores, as planar faces in the half-plane (origin, axis, radial),
  // each with normal axis x radial (its wires counter-clockwise about it).
  std::unique_ptr<Solid> section;
  std::vector<RevolutionCore> cores;
  double core_radius = 0;  // 0 when the section does not touch the axis
  // Per edge of `section`: it is the side of a core (r = core_radius), inside the solid.
  std::vector<bool> core_side;
  double height(const Vec3& p) const { return (p - origin).dot(axis); }
  double radius(const Vec3& p) const {
    const Vec3 d = p - origin;
    return (d - d.dot(axis) * axis).norm();
  }
};

// Tries the axes of the solid's cylinders, cones, tori and surfaces of revolution. Never
// throws for geometry it cannot handle: ok false with the reason.
RevolutionStructure revolution_structure(const core::MeshDomain& solid);

}  // namespace vorohex::occ
