// The cylinders through the feet of concave round fillets and chamfers on their floors (and
// beyond a round pocket's wall): a boss whose root is filleted (a torus meeting the plate's top
// tangentially) or chamfered (a cone meeting it at a concave edge), each in FreeCAD's Fillet and
// Chamfer (tests/data/plate_boss_root_fillet.step, plate_boss_root_chamfer.step); a countersink's
// cone meets the top at a convex edge and gives none.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "decompose/detail/foot_planes.h"
#include "fixtures/machined.h"
#include "fixtures/solids.h"
#include "occ/shape_io.h"

namespace vorohex::decompose::detail {
namespace {

occ::Solid read(const std::string& name) {
  return testing::read_test_data(name);
}

// 60 x 40 x 10 with a boss of radius 8 at (30, 20), its root filleted or chamfered by 2: the
// foot on the plate is the circle of radius 10 at z = 10, the cylinder along z through it.
void expect_the_boss_foot(const occ::Solid& s) {
  const std::vector<FootCylinder> feet = foot_cylinders(s);
  ASSERT_EQ(feet.size(), 1u);  // no ring: the boss's side bulges out
  EXPECT_FALSE(feet[0].ring);
  const occ::CutCylinder& c = feet[0].surface;
  EXPECT_NEAR(c.radius, 10, 1e-6);
  EXPECT_NEAR(std::abs(c.axis.z()), 1, 1e-9);
  EXPECT_NEAR(c.origin.x(), 30, 1e-6);
  EXPECT_NEAR(c.origin.y(), 20, 1e-6);
  // Along the whole solid, its seam through the foot circle's vertex.
  const double z0 = c.origin.z() + c.from * c.axis.z(), z1 = c.origin.z() + c.to * c.axis.z();
  EXPECT_LT(std::min(z0, z1), 0);
  EXPECT_GT(std::max(z0, z1), 25);
  const core::Vec3 vertex = s.vertex_point(s.edge_first_vertex(feet[0].edge));
  const core::Vec3 d = vertex - c.origin;
  EXPECT_NEAR((d - d.dot(c.axis) * c.axis).normalized().dot(c.seam), 1, 1e-9);
}

TEST(FootCylinders, ABossWithItsRootFilletedOrChamferedHasOne) {
  {
    SCOPED_TRACE("filleted");
    expect_the_boss_foot(read("plate_boss_root_fillet.step"));
  }
  {
    SCOPED_TRACE("chamfered");
    expect_the_boss_foot(read("plate_boss_root_chamfer.step"));
  }
}

// A 60 x 40 x 20 block with a round pocket of radius 10 and depth 10 whose floor is filleted
// by 2 (tests/data/round_pocket_floor_fillet.step): the cylinder through the foot on the floor
// (radius 8), and the ring's beyond the wall as far as that (radius 12), both seamed at the
// foot circle's vertex.
TEST(FootCylinders, ARoundPocketsFloorFilletHasOneOnTheFloorAndOneBeyondTheWall) {
  const occ::Solid s = read("round_pocket_floor_fillet.step");
  const std::vector<FootCylinder> feet = foot_cylinders(s);
  ASSERT_EQ(feet.size(), 2u);
  EXPECT_FALSE(feet[0].ring);
  EXPECT_NEAR(feet[0].surface.radius, 8, 1e-6);
  EXPECT_TRUE(feet[1].ring);
  EXPECT_NEAR(feet[1].surface.radius, 12, 1e-6);
  EXPECT_NEAR(feet[0].surface.seam.dot(feet[1].surface.seam), 1, 1e-12);
}

TEST(FootCylinders, ACountersinkOrAHoleEdgeFilletHasNone) {
  EXPECT_TRUE(foot_cylinders(testing::make_block_with_countersunk_hole()).empty());
  // The hole's top edge filleted: a torus that bulges out of the solid.
  EXPECT_TRUE(foot_cylinders(read("plate_hole_edge_fillet.step")).empty());
}

}  // namespace
}  // namespace vorohex::decompose::detail
