// Where a face comes to a point (core/face_cusp.h: a crescent between a circle and a larger
// one tangent to it, a plate's outline tangent to a hole), the domain near the point is a
// strip narrower than a node spacing for several spacings. Any inner node there makes quads
// that fold (HexMe i11: every quad mesher variant folded in the crescent's tail). A ladder
// instead: quads of four boundary nodes each, peeled off the loop from the point (the quad at
// the point, then rung after rung, each quad taking two nodes of one side or one of each),
// until the strip is as wide as a good part of the size. The rest of the face is meshed as
// before, with the last rung as a straight piece of its boundary.
#pragma once

#include <array>
#include <vector>

#include "mesh/detail/quad_mesh_2d.h"

namespace vorohex::mesh::detail {

struct CuspLadders {
  // The loops left to mesh (each still even, at least 6 nodes, or 4 for a single loop), and
  // for each of their nodes its index among the given loops' nodes (in order, as in
  // QuadMesh2d::points).
  std::vector<std::vector<Vec2>> loops;
  std::vector<std::vector<int>> index;
  // The ladders' quads, counter-clockwise, on the given nodes' indices; empty: no point.
  std::vector<std::array<int, 4>> quads;
};

// Ladders from every node of `loops` (the domain on their left) whose interior angle is
// below about 9 degrees. `size`: the target edge length (a ladder stops where its rung is
// 0.4 x size long, or where no next quad is valid, or its rung would cross a boundary).
CuspLadders cusp_ladders(const std::vector<std::vector<Vec2>>& loops, double size);

}  // namespace vorohex::mesh::detail
