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

// Extrusion along +z by `depth` of an annulus sector around the z axis from angle 0 to
// `angle` (radians, < pi): a topological block with two cylindrical faces.
Solid make_ring_sector(double inner_radius, double outer_radius, double angle, double depth);

}  // namespace vorohex::occ
