// occ::tessellate: the result depends on the solid and the options only, not on earlier
// calls (OCCT keeps a finer triangulation stored on the shape unless it is removed).
#include "occ/tessellate.h"

#include <gtest/gtest.h>

#include "occ/primitives.h"

namespace vorohex {
namespace {

std::size_t triangles(const occ::Tessellation& t) {
  std::size_t n = 0;
  for (const occ::FaceTriangulation& f : t.faces) n += f.triangles.size();
  return n;
}

TEST(Tessellate, AnEarlierFinerTessellationDoesNotCarryOver) {
  const occ::Solid cylinder = occ::make_cylinder(1, 2);
  occ::TessellationOptions coarse, fine;
  coarse.linear_deflection = 0.05;
  fine.linear_deflection = 0.001;
  const occ::Tessellation first = occ::tessellate(cylinder, coarse);
  ASSERT_TRUE(first.ok());
  const occ::Tessellation detailed = occ::tessellate(cylinder, fine);
  ASSERT_TRUE(detailed.ok());
  ASSERT_GT(triangles(detailed), triangles(first));
  const occ::Tessellation again = occ::tessellate(cylinder, coarse);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(triangles(again), triangles(first));
  for (std::size_t f = 0; f < first.faces.size(); ++f)
    EXPECT_EQ(again.faces[f].nodes.size(), first.faces[f].nodes.size()) << "face " << f;
}

}  // namespace
}  // namespace vorohex
