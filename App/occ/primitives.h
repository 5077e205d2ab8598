// Solids built from parameters: test fixtures, examples and benchmarks.
#pragma once

#include <array>
#include <vector>

#include "occ/solid.h"

namespace vorohex::occ {

// Axis-aligned box with one corner at the origin.
Solid make_box(double dx, double dy, double dz);

// A brick whose bottom is the rectangle [0,dx]x[0,dy] at z=0 and whose top is the
// rectangle shrunk by `taper` on every side at z=dz: six planar faces.
Solid make_tapered_brick(double dx, double dy, double dz, double taper);

// A planar polyhedron: points and faces (each a list of point indices, any orientation).
Solid make_polyhedron(const std::vector<Vec3>& points, const std::vector<std::vector<int>>& faces);

// Extrusion along +z by `depth` of a simple polygon in the xy-plane (counter-clockwise),
// with optional polygonal holes (any orientation).
Solid make_prism(const std::vector<std::array<double, 2>>& outline, double depth,
                 const std::vector<std::vector<std::array<double, 2>>>& holes = {});

// Cylinder of the given radius and height on the z axis.
Solid make_cylinder(double radius, double height);

// Box with its minimum corner at `corner`.
Solid make_box(double dx, double dy, double dz, const Vec3& corner);

// Cylinder and cone (radius r1 at the base, r2 at the top, one of them may be 0) on the
// axis through `base` along `axis` (any length, not 0).
Solid make_cylinder(double radius, double height, const Vec3& base, const Vec3& axis);
Solid make_cone(double r1, double r2, double height, const Vec3& base, const Vec3& axis);
// Torus of major radius R and minor radius r (0 < r < R) about the axis through `centre`.
Solid make_torus(double major, double minor, const Vec3& centre, const Vec3& axis);

// The solid of revolution about the z axis of a simple polygon in the (r, z) half-plane
// (r >= 0; edges on r = 0 lie on the axis), turned by a full turn: a turned part.
Solid make_revolved(const std::vector<std::array<double, 2>>& rz);

// Extrusion along +z by `depth` of an annulus sector around the z axis from angle 0 to
// `angle` (radians, < 2 pi): a topological block with two cylindrical faces.
Solid make_ring_sector(double inner_radius, double outer_radius, double angle, double depth);

}  // namespace vorohex::occ
