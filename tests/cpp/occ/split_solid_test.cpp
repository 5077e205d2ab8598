#include "occ/split_solid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "occ/primitives.h"
#include "occ/shape_io.h"

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

// A block with two crossing round holes (the Steinmetz solid where they meet), split by a
// plane below both axes: the pieces' volumes sum to the exact
// volume to 1e-9, as the decomposition's self-check requires. OCCT's fixed-order volume
// integration erred by 1e-7 on such trimmed cylinders and failed that check.
TEST(SplitSolid, PieceVolumesOfCurvedSolidsSumToTheExactVolume) {
  const double pi = 3.14159265358979323846;
  std::unique_ptr<Solid> block =
      cut_solids(make_box(20, 20, 20), make_cylinder(4, 20, Vec3(10, 0, 10), Vec3(0, 1, 0)));
  ASSERT_TRUE(block);
  block = cut_solids(*block, make_cylinder(4, 20, Vec3(0, 10, 10), Vec3(1, 0, 0)));
  ASSERT_TRUE(block);
  const double exact = 8000 - 2 * pi * 16 * 20 + 16.0 * 64 / 3;
  EXPECT_NEAR(block->volume(), exact, 1e-10 * exact);
  const SplitResult split = split_solid(
      *block, {{Vec3(-1, -1, 7), Vec3(21, -1, 7), Vec3(21, 21, 7), Vec3(-1, 21, 7)}}, 1e-7);
  ASSERT_EQ(split.pieces.size(), 2u);
  double sum = 0;
  for (const Solid& piece : split.pieces) sum += piece.volume();
  EXPECT_NEAR(sum, exact, 1e-9 * exact);
}

// A box cut at x = 1 and x = 2, its first two pieces merged back: the solid split afresh at
// the faces the merged piece and the third share is that face alone, two pieces of six faces
// with the merged ones' volumes; nothing where the pieces share no face.
TEST(SplitSolid, SplitAfreshAtTheFacesMergedPiecesShare) {
  const Solid box = make_box(3, 1, 1);
  const SplitResult cut =
      split_solid(box,
                  {{Vec3(1, -1, -1), Vec3(1, 2, -1), Vec3(1, 2, 2), Vec3(1, -1, 2)},
                   {Vec3(2, -1, -1), Vec3(2, 2, -1), Vec3(2, 2, 2), Vec3(2, -1, 2)}},
                  1e-7);
  ASSERT_TRUE(cut.ok);
  ASSERT_EQ(cut.pieces.size(), 3u);
  std::vector<const Solid*> low, high;
  for (const Solid& p : cut.pieces) (p.bounding_box().max.x() < 2.5 ? low : high).push_back(&p);
  ASSERT_EQ(low.size(), 2u);
  const std::unique_ptr<Solid> merged = fuse_solids(*low[0], *low[1]);
  ASSERT_TRUE(merged);
  const ReadResult glued = glue_solids({merged.get(), high[0]}, "The test");
  ASSERT_TRUE(glued.ok());
  const SplitResult afresh = split_at_interfaces(box, *glued.solid, 1e-7);
  ASSERT_TRUE(afresh.ok);
  ASSERT_EQ(afresh.pieces.size(), 2u);
  for (const Solid& p : afresh.pieces) {
    EXPECT_TRUE(is_closed(p));
    EXPECT_EQ(p.num_faces(), 6);
    EXPECT_EQ(p.num_vertices(), 8);
    const double v = p.volume();
    EXPECT_TRUE(std::abs(v - 2) < 1e-9 || std::abs(v - 1) < 1e-9) << v;
  }
  EXPECT_FALSE(split_at_interfaces(box, box, 1e-7).ok);
}

// A Fuser's unions, one child process for them all, are fuse_solids' own: a row of boxes
// fused one by one into one box of six faces (its split faces unified), and a post on a plate.
TEST(Fuser, UnionsInOneChildAreFuseSolidsOwn) {
  Fuser fuser;
  std::unique_ptr<Solid> row = std::make_unique<Solid>(make_box(1, 1, 1));
  for (int k = 1; k < 6; ++k) {
    row = fuser.fuse(*row, make_box(1, 1, 1, Vec3(k, 0, 0)), 10);
    ASSERT_TRUE(row) << "union " << k;
    EXPECT_EQ(row->num_faces(), 6) << "union " << k;
    EXPECT_NEAR(row->volume(), k + 1.0, 1e-12);
  }
  const Solid plate = make_box(4, 4, 1);
  const Solid post = make_cylinder(1, 3, Vec3(2, 2, 0), Vec3(0, 0, 1));
  const std::unique_ptr<Solid> a = fuser.fuse(plate, post, 10);
  const std::unique_ptr<Solid> b = fuse_solids(plate, post, 10);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->num_faces(), b->num_faces());
  EXPECT_NEAR(a->volume(), b->volume(), 1e-12 * b->volume());
  EXPECT_EQ(fuser.children(), 1);
  // Boxes meeting only along an edge are no one solid.
  EXPECT_FALSE(fuser.fuse(make_box(1, 1, 1), make_box(1, 1, 1, Vec3(1, 1, 0)), 10));
}

}  // namespace
}  // namespace vorohex::occ
