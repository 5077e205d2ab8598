// Feature capture's vertex assignment (grid/detail/features.h): nodes taken nearest first,
// vertex after vertex, are uncrossed so that vertices on a line keep their order.
#include "grid/detail/features.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace vorohex
