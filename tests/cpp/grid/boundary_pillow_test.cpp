// The second pillow layer under a mesh's boundary (grid/boundary_pillow.h): the
// boundary stays where it was, every boundary quad gets a new hexahedron with exactly one
// boundary quad, the mesh stays conforming and closed, and a hexahedron whose two faces lay on
// the boundary at a flat angle (a doublet) no longer has two boundary faces.
#include "grid/boundary_pillow.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "../quality/grid_fixture.h"
#include "core/hex_mesh.h"
#include "quality/check_mesh.h"
#include "quality/scaled_jacobian.h"

namespace vorohex {
namespace {

using grid::pillow_boundary;

void expect_conforming(const core::HexMesh& m, double volume) {
  const quality::CheckReport c = quality::check_mesh(m, nullptr);
  EXPECT_EQ(c.non_positive, 0u);
  EXPECT_EQ(c.non_manifold_quads, 0u);
  EXPECT_EQ(c.folded_quads, 0u);
  EXPECT_EQ(c.open_boundary_edges, 0u);
  EXPECT_EQ(c.unused_nodes, 0u);
  EXPECT_NEAR(c.mesh_volume, volume, 1e-9 * volume);
}

TEST(BoundaryPillow, BoxGetsOneLayerPerBoundaryQuad) {
  core::HexMesh m = quality::testing::structured_grid(3, 2, 2);
  const std::size_t boundary = core::boundary_faces(m).size();  // 2*(6 + 6 + 4) = 32
  ASSERT_EQ(boundary, 32u);
  const std::vector<core::Vec3> before = m.points();
  const auto r = pillow_boundary(m, 0.3);
  EXPECT_EQ(r.hexes_added, boundary);
  EXPECT_EQ(m.num_hexes(), 12u + boundary);
  // The twins of the boundary nodes: all but the 2 interior nodes (3 x 3 x 4 = 36 nodes).
  EXPECT_EQ(r.nodes_added, 36u - 2u);
  EXPECT_EQ(m.num_nodes(), 36u + r.nodes_added);
  expect_conforming(m, 12.0);
  // The boundary is the old one: its nodes did not move and are still the boundary's.
  const std::vector<char> on = core::boundary_nodes(m);
  for (std::size_t v = 0; v < before.size(); ++v) {
    const bool was = before[v].x() == 0 || before[v].x() == 3 || before[v].y() == 0 ||
                     before[v].y() == 2 || before[v].z() == 0 || before[v].z() == 2;
    EXPECT_EQ(bool(on[v]), was) << "node " << v;
    EXPECT_EQ(m.point(core::NodeId{std::int32_t(v)}), before[v]);
  }
  for (std::size_t v = before.size(); v < m.num_nodes(); ++v) EXPECT_FALSE(on[v]) << "twin " << v;
  // Each hexahedron has at most one boundary quad now.
  std::vector<int> boundary_quads(m.num_hexes(), 0);
  for (const core::BoundaryFace& f : core::boundary_faces(m)) ++boundary_quads[f.hex];
  for (int n : boundary_quads) EXPECT_LE(n, 1);
  // A face node's twin lies on its one interior edge at the shrink: the layer is 0.3 thick.
  const std::vector<double> sj = quality::scaled_jacobians(m);
  for (double v : sj) EXPECT_GT(v, 0.2);
}

// One hexahedron, all six faces on the boundary, one face sloped: pillowed, it is inside and
// each of the six new hexahedra has exactly one boundary quad (no two boundary faces meet in
// one hexahedron any more), all positive, the volume unchanged.
TEST(BoundaryPillow, LoneHexahedronGetsSixAroundIt) {
  core::HexMesh m;
  const double a = 10 * M_PI / 180;  // the face x = 1 leans out by 10 degrees
  const core::Vec3 p[8] = {{0, 0, 0},
                           {1, 0, 0},
                           {1, 1, 0},
                           {0, 1, 0},
                           {0, 0, 1},
                           {1 + std::tan(a), 0, 1},
                           {1 + std::tan(a), 1, 1},
                           {0, 1, 1}};
  for (const core::Vec3& q : p) m.add_node(q);
  m.add_hex({0, 1, 2, 3, 4, 5, 6, 7});
  const double volume = quality::check_mesh(m, nullptr).mesh_volume;
  const auto r = pillow_boundary(m);
  EXPECT_EQ(r.hexes_added, 6u);
  EXPECT_EQ(r.nodes_added, 8u);
  expect_conforming(m, volume);
  std::vector<int> boundary_quads(m.num_hexes(), 0);
  for (const core::BoundaryFace& f : core::boundary_faces(m)) ++boundary_quads[f.hex];
  EXPECT_EQ(boundary_quads[0], 0);  // the old hexahedron is inside now
  for (std::size_t h = 1; h < m.num_hexes(); ++h) EXPECT_EQ(boundary_quads[h], 1);
  for (double v : quality::scaled_jacobians(m)) EXPECT_GT(v, 0.5);
}

// A hexahedron with two boundary quads across an edge whose normals differ by less than the
// angle given is a flat doublet: a box's corner hexahedra (90 degrees) are not at 30, are at
// 100; a hexahedron whose top face is bent down to 160 degrees at an edge with its side is.
TEST(BoundaryPillow, FlatDoubletsAreTwoBoundaryQuadsNearlyFlatAcrossAnEdge) {
  const core::HexMesh box = quality::testing::structured_grid(3, 2, 2);
  EXPECT_EQ(grid::flat_doublets(box, 30), 0u);
  EXPECT_EQ(grid::flat_doublets(box, 100), box.num_hexes());  // every one is on a corner or edge
  core::HexMesh m;
  // The face x = 1 leans in by 70 degrees: its normal turns 20 degrees from the top's (z).
  const double t = std::tan(70 * M_PI / 180);
  const core::Vec3 p[8] = {{0, 0, 0}, {1 + t, 0, 0}, {1 + t, 1, 0}, {0, 1, 0},
                           {0, 0, 1}, {1, 0, 1},     {1, 1, 1},     {0, 1, 1}};
  for (const core::Vec3& q : p) m.add_node(q);
  m.add_hex({0, 1, 2, 3, 4, 5, 6, 7});
  EXPECT_EQ(grid::flat_doublets(m, 30), 1u);
  EXPECT_EQ(grid::flat_doublets(m, 15), 0u);
}

TEST(BoundaryPillow, RejectsShrinkOutsideTheUnitInterval) {
  core::HexMesh m = quality::testing::structured_grid(1, 1, 1);
  EXPECT_THROW(pillow_boundary(m, 0.0), std::invalid_argument);
  EXPECT_THROW(pillow_boundary(m, 1.0), std::invalid_argument);
  EXPECT_EQ(m.num_hexes(), 1u);  // untouched
  core::HexMesh empty;
  EXPECT_EQ(pillow_boundary(empty).hexes_added, 0u);
}

}  // namespace
}  // namespace vorohex
