// The planes of the strips that concave fillets along floors lie on, ended at their mitres: a
// plate with a rectangular pocket whose floor edges are filleted, and one with a rectangular
// boss whose root is, each in FreeCAD's Fillet (tests/data/pocket_floor_fillet.step,
// plate_rect_boss_root_fillet.step); a block whose top edges are filleted (convex fillets)
// and a round pocket's floor (a torus) give none.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "decompose/detail/fillet_strips.h"
#include "fixtures/solids.h"
#include "occ/shape_io.h"

namespace vorohex::decompose::detail {
namespace {

occ::Solid read(const std::string& name) {
  return testing::read_test_data(name);
}

// The offsets of the whole planes of `kind` with normal along axis `a` (0 x, 1 y), sorted.
std::vector<double> offsets(const FilletStrips& s, StripPlane::Kind kind, int a) {
  std::vector<double> out;
  for (const StripPlane& p : s.planes)
    if (p.kind == kind && std::abs(std::abs(p.normal[a]) - 1) < 1e-9)
      out.push_back(std::abs(p.offset));
  std::sort(out.begin(), out.end());
  return out;
}

void expect_near(const std::vector<double>& got, const std::vector<double>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t k = 0; k < got.size(); ++k) EXPECT_NEAR(got[k], want[k], 1e-6);
}

// 60 x 40 x 15, a pocket 30 x 20 x 8 from (15, 10, 7), its floor edges filleted with radius 3:
// the feet on the floor at x = 18, 42 and y = 13, 27, the planes beyond the walls at x = 12,
// 48 and y = 7, 33; at each corner a mitre from where the feet cross to where the far planes
// do, across the whole height.
TEST(FilletStrips, APocketsFloorFilletsLieOnStripsEndedAtMitres) {
  const occ::Solid s = read("pocket_floor_fillet.step");
  const FilletStrips strips = fillet_strips(s);
  EXPECT_EQ(strips.fillets.size(), 4u);
  EXPECT_EQ(strips.tangent_faces.size(), 5u);  // the floor and the four walls
  expect_near(offsets(strips, StripPlane::across, 0), {18, 42});
  expect_near(offsets(strips, StripPlane::across, 1), {13, 27});
  expect_near(offsets(strips, StripPlane::beyond, 0), {12, 48});
  expect_near(offsets(strips, StripPlane::beyond, 1), {7, 33});
  int mitres = 0;
  for (const StripPlane& p : strips.planes) {
    if (p.kind != StripPlane::mitre) {
      EXPECT_TRUE(p.quad.empty());
      continue;
    }
    ++mitres;
    ASSERT_EQ(p.quad.size(), 4u);
    EXPECT_EQ(p.edges.size(), 1u);  // the edge where the two fillets meet
    // Its corners: above and below the two crossings, at 45 degrees to the walls.
    const core::Vec3 in = p.quad[0], out = p.quad[1];
    EXPECT_NEAR(std::abs(in.x() - out.x()), 6, 1e-6);
    EXPECT_NEAR(std::abs(in.y() - out.y()), 6, 1e-6);
    EXPECT_TRUE(std::abs(in.x() - 18) < 1e-6 || std::abs(in.x() - 42) < 1e-6);
    EXPECT_TRUE(std::abs(in.y() - 13) < 1e-6 || std::abs(in.y() - 27) < 1e-6);
    EXPECT_LT(std::min(in.z(), p.quad[2].z()), 0);
    EXPECT_GT(std::max(in.z(), p.quad[2].z()), 15);
  }
  EXPECT_EQ(mitres, 4);
}

// 60 x 40 x 10 with a boss 24 x 12 x 8 from (18, 14), its root filleted with radius 2: the
// feet on the plate outside the boss, the far planes inside it.
TEST(FilletStrips, ABossRootFilletsLieOnStripsToo) {
  const FilletStrips strips = fillet_strips(read("plate_rect_boss_root_fillet.step"));
  expect_near(offsets(strips, StripPlane::across, 0), {16, 44});
  expect_near(offsets(strips, StripPlane::across, 1), {12, 28});
  expect_near(offsets(strips, StripPlane::beyond, 0), {20, 40});
  expect_near(offsets(strips, StripPlane::beyond, 1), {16, 24});
}

// The same pocket with its vertical corners rounded by 5 before its floor (FreeCAD's Fillet
// twice): the floor fillet turns round each corner on a surface of revolution. The straight
// strips' planes are quads between the corners' axes, and at each corner the strip turns on a
// quarter of a ring between the cylinder through the foot (radius 2) and the one as far beyond
// the corner's wall (radius 8), ended by the planes through the corner's axis.
TEST(FilletStrips, APocketsRoundedCornersTurnTheStripsOnSectorsOfRings) {
  const FilletStrips strips = fillet_strips(read("pocket_rounded_corners_floor_fillet.step"));
  expect_near(offsets(strips, StripPlane::across, 0), {18, 42});
  expect_near(offsets(strips, StripPlane::beyond, 1), {7, 33});
  int corners = 0;
  for (const StripPlane& p : strips.planes) {
    EXPECT_NE(p.kind, StripPlane::mitre);
    EXPECT_EQ(p.quad.size(), 4u);  // all bounded: the straight strips end at the corners
    corners += p.kind == StripPlane::corner;
  }
  EXPECT_EQ(corners, 8);
  ASSERT_EQ(strips.cylinders.size(), 8u);
  for (const StripCylinder& c : strips.cylinders) {
    EXPECT_NEAR(c.surface.radius, c.beyond ? 8 : 2, 1e-6);
    EXPECT_NEAR(c.surface.angle, M_PI / 2, 1e-6);
    EXPECT_NEAR(std::abs(c.surface.axis.z()), 1, 1e-9);
    const double x = c.surface.origin.x(), y = c.surface.origin.y();
    EXPECT_TRUE(std::abs(x - 20) < 1e-6 || std::abs(x - 40) < 1e-6) << x;
    EXPECT_TRUE(std::abs(y - 15) < 1e-6 || std::abs(y - 25) < 1e-6) << y;
  }
}

TEST(FilletStrips, ConvexFilletsAndARoundPocketsFloorHaveNone) {
  EXPECT_TRUE(fillet_strips(read("block_top_fillets.step")).planes.empty());
  EXPECT_TRUE(fillet_strips(read("round_pocket_floor_fillet.step")).planes.empty());
  EXPECT_TRUE(fillet_strips(read("plate_boss_root_fillet.step")).planes.empty());
}

}  // namespace
}  // namespace vorohex::decompose::detail
