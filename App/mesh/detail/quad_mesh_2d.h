// The planar core of quad_face: an all-quad mesh of a polygonal domain with holes whose
// boundary nodes are given and kept. Method: a constrained Delaunay triangulation (CGAL, no
// refinement) of every other boundary node plus a square lattice at twice the target size
// aligned with the boundary's dominant direction; pairs of triangles that make good quads
// are merged; every triangle is split into 3 quads and every quad into 4 (edge midpoints
// and centre), so the skipped boundary nodes come back as the boundary edges' midpoints;
// then quality-guarded smoothing of the inner nodes. Before that, up to `ring_layers` rings
// of quads are laid along each loop without sharp corners (a round hole, a circular outline):
// each ring offsets the loop's nodes into the domain by about one segment, so the quads next
// to a hole follow it (an O-grid) instead of a lattice cut by it. A ring is kept only while
// it is well shaped, a ring's width clear of the other loops, and its segments between
// 0.7 and 2 x size.
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <string>
#include <vector>

namespace vorohex::mesh::detail {

using Vec2 = Eigen::Vector2d;
// A local target size at a point of the domain (at most the global size); empty: uniform.
using SizeAt = std::function<double(const Vec2&)>;

struct QuadMesh2d {
  std::vector<Vec2> points;               // the boundary nodes (loops in order), then inner nodes
  std::vector<std::array<int, 4>> quads;  // counter-clockwise
  std::string error;                      // empty on success
};

// loops: closed cycles of boundary nodes (first not repeated), the domain on their left
// (outer counter-clockwise, holes clockwise). Each loop needs an even number of nodes, at
// least 6, except a domain of one loop with 4 nodes (one quad; five, pillowed, where one of
// the four has a straight angle). size: target edge length;
// size_at, when given, a smaller local size: the lattice becomes a balanced quadtree whose
// cells follow it (a graded mesh).
QuadMesh2d quad_mesh_2d(const std::vector<std::vector<Vec2>>& loops, double size,
                        int smoothing_passes, int ring_layers = 0, const SizeAt& size_at = {});

// 2-D quad scaled Jacobian: the minimum over the corners of the cross product of the two
// corner edges divided by their lengths (1 for a square, <= 0 when inverted or collapsed).
double quad_quality(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d);

}  // namespace vorohex::mesh::detail
