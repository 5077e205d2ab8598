// Feature capture (grid/detail/features.h): nodes taken nearest first, vertex after vertex,
// are uncrossed so that vertices on a line keep their order; the quads a vertex's node
// needs for its faces' angles; the face a region of quads goes on.
#include "grid/detail/features.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vorohex {
namespace {

using core::Vec3;

TEST(FeatureCapture, VerticesOnALineKeepTheirOrderOnTheirNodes) {
  // Three vertices 5 apart on a line (HexMe i21's Vertex39, Vertex58, Vertex59 at a size of
  // 3.3); the middle one chose first and took the node beyond the third.
  const std::vector<Vec3> targets = {Vec3(0, 0, 0), Vec3(0, 5, 0), Vec3(0, 10, 0)};
  std::vector<Vec3> positions = {Vec3(0.5, 0.4, 0), Vec3(0.3, 9.1, 0.2), Vec3(0.2, 6.2, 0.1)};
  std::vector<std::int32_t> nodes = {11, 12, 13};
  EXPECT_EQ(grid::detail::uncross(targets, positions, nodes, 13.4), 1u);
  EXPECT_EQ(nodes, (std::vector<std::int32_t>{11, 13, 12}));
  for (std::size_t i = 0; i + 1 < targets.size(); ++i)
    EXPECT_LT(positions[i].y(), positions[i + 1].y()) << i;
  // Already in order: nothing moves. Farther apart than the reach: left as they are.
  EXPECT_EQ(grid::detail::uncross(targets, positions, nodes, 13.4), 0u);
  std::vector<Vec3> crossed = {Vec3(0, 9, 0), Vec3(0, 5, 0), Vec3(0, 1, 0)};
  std::vector<std::int32_t> far_nodes = {1, 2, 3};
  EXPECT_EQ(grid::detail::uncross(targets, crossed, far_nodes, 4.0), 0u);
  EXPECT_EQ(far_nodes, (std::vector<std::int32_t>{1, 2, 3}));
}

TEST(FeatureCapture, AFlatOrReflexAngleAtAVertexNeedsMoreThanOneQuad) {
  auto deg = [](double a) { return a * M_PI / 180; };
  // A box's corner, a pyramid's apex: one quad per face.
  EXPECT_EQ(grid::detail::quads_for_angle(deg(90)), 1);
  EXPECT_EQ(grid::detail::quads_for_angle(deg(30)), 1);
  EXPECT_EQ(grid::detail::quads_for_angle(deg(165)), 1);
  // A face flat at a vertex (an edge running on straight through it: HexMe i13, s10): two,
  // or the one quad there would have both chains along two of its sides, flat.
  EXPECT_EQ(grid::detail::quads_for_angle(deg(175)), 2);
  EXPECT_EQ(grid::detail::quads_for_angle(deg(180)), 2);
  // A floor at 191 degrees where walls meet it (HexMe i17): one quad there would be bent
  // inside out. n06's pit rim (252) two, i19's 267 three, the floor around a boss's corner
  // (270) three, a slit's end (360) three.
  EXPECT_EQ(grid::detail::quads_for_angle(deg(191)), 2);
  EXPECT_EQ(grid::detail::quads_for_angle(deg(252)), 2);
  EXPECT_EQ(grid::detail::quads_for_angle(deg(267)), 3);
  EXPECT_EQ(grid::detail::quads_for_angle(deg(270)), 3);
  EXPECT_EQ(grid::detail::quads_for_angle(deg(360)), 3);
}

TEST(FeatureCapture, ARegionGoesOnAFaceThatBordersEveryChainAroundIt) {
  // Edge 85 bounds faces 17 and 27, edge 96 faces 20 and 27 (HexMe i13: a strip between
  // them, on face 27, whose free nodes had voted 20 and 27 once each).
  const std::map<int, std::set<int>> faces_of = {{85, {17, 27}}, {96, {20, 27}}};
  auto borders = [&](int f, int e) { return faces_of.at(e).count(f) > 0; };
  EXPECT_EQ(grid::detail::region_face({{20, 1}, {27, 1}}, {85, 96}, borders), 27);
  // The winner borders them all: it stays, whatever the others.
  EXPECT_EQ(grid::detail::region_face({{27, 5}, {20, 9}}, {96}, borders), 20);
  // No face with votes borders them all (a region leaked across an uncaptured edge): the
  // vote stands.
  EXPECT_EQ(grid::detail::region_face({{20, 4}, {17, 2}}, {85, 96}, borders), 20);
  // No chain around it (a closed surface): the vote.
  EXPECT_EQ(grid::detail::region_face({{3, 2}, {4, 7}}, {}, borders), 4);
  EXPECT_EQ(grid::detail::region_face({}, {85}, borders), -1);
}

}  // namespace
}  // namespace vorohex
