#include "occ/split_solid.h"

#include <gtest/gtest.h>

#include "occ/primitives.h"

namespace vorohex::occ {
namespace {

// A cut through the whole box and a square floating inside the lower half: two closed
// pieces, the floating square dropped (it separates nothing). OCCT puts such a face in a
// shell of its own; dropping it must not leave an empty shell behind (a piece with an
// empty shell is "not closed", which failed the Figure 6 part's decomposition).
TEST(SplitSolid, DanglingToolFacesAreDroppedAndPiecesStayClosed) {
  const Solid box = make_box(2, 2, 2);
  const std::vector<std::vector<Vec3>> tools = {
      {Vec3(-1, -1, 1), Vec3(3, -1, 1), Vec3(3, 3, 1), Vec3(-1, 3, 1)},
      {Vec3(0.5, 0.5, 0.5), Vec3(1.5, 0.5, 0.5), Vec3(1.5, 1.5, 0.5), Vec3(0.5, 1.5, 0.5)}};
  const SplitResult r = split_solid(box, tools, 1e-7);
  ASSERT_TRUE(r.ok);
  ASSERT_EQ(r.pieces.size(), 2u);
  EXPECT_GE(r.dropped_internal_faces, 1);
  double sum = 0;
  for (const Solid& p : r.pieces) {
    EXPECT_TRUE(is_closed(p));
    EXPECT_EQ(p.num_faces(), 6);
    EXPECT_NEAR(p.volume(), 4.0, 1e-12);
    sum += p.volume();
  }
  EXPECT_NEAR(sum, 8.0, 1e-12);
}

}  // namespace
}  // namespace vorohex::occ
