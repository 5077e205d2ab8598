#include "mesh/submap_face.h"

#include <gtest/gtest.h>

#include "fixtures/solids.h"
#include "mesh/sweep.h"
#include "occ/primitives.h"

namespace vorohex::mesh {
namespace {

// The face of a prism lying at z = depth (its top): the source of a sweep through it.
core::FaceId top_face(const occ::Solid& s) {
  for (core::FaceId f : s.faces())
    if (s.face_is_planar(f) && s.face_normal(f, s.vertex_point(core::VertexId(1))).z() > 0.99)
      return f;
  return core::FaceId();
}

TEST(SubmapFace, RectilinearOutlinesGetDirectionsOthersNone) {
  const occ::Solid l = testing::make_l(3);
  const core::FaceId top = top_face(l);
  ASSERT_TRUE(top.valid());
  const std::vector<int> dirs = submap_directions(l, top);
  ASSERT_EQ(dirs.size(), 6u);
  int count[4] = {0, 0, 0, 0};
  for (int d : dirs) ++count[d];
  // An L has two edges in each of two directions and one in each of the others.
  EXPECT_EQ(count[0] + count[2], 3);
  EXPECT_EQ(count[1] + count[3], 3);
  // A box's faces are four-sided (mapped, not submapped); a 45-degree corner is no corner.
  const occ::Solid box = occ::make_box(2, 1, 1);
  for (core::FaceId f : box.faces()) EXPECT_TRUE(submap_directions(box, f).empty());
  const occ::Solid chamfered =
      occ::make_prism({{0, 0}, {4, 0}, {4, 1}, {1, 1}, {0.5, 2}, {0, 2}}, 1);
  EXPECT_TRUE(submap_directions(chamfered, top_face(chamfered)).empty());
}

// L, T and U extrusions swept with a submapped source: every quad a rectangle, so every
// hex a perfect box; counts balanced by one interval assignment.
TEST(SubmapFace, SweptExtrusionsAreAllRectangles) {
  struct Case {
    const char* name;
    occ::Solid solid;
    std::size_t hexes;  // area / size^2 per layer, times the layers
  };
  std::vector<Case> cases;
  cases.push_back({"L", testing::make_l(3), 96u * 12u});
  cases.push_back({"T", testing::make_t(), 128u * 8u});
  cases.push_back({"U", testing::make_u(), 176u * 8u});
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    SweepOptions o;
    o.size = 0.25;
    const SweepResult r = sweep(c.solid, o);
    ASSERT_TRUE(r.ok);
    EXPECT_NEAR(r.source_min_quality, 1.0, 1e-9);
    EXPECT_EQ(r.mesh.num_hexes(), c.hexes);
  }
}

TEST(SubmapFace, UnbalancedCountsAreRefused) {
  const occ::Solid l = testing::make_l(3);
  const core::FaceId top = top_face(l);
  const std::vector<int> dirs = submap_directions(l, top);
  ASSERT_EQ(dirs.size(), 6u);
  std::vector<int> counts(6, 2);
  std::vector<core::Vec3> loop(12, core::Vec3::Zero());
  const QuadFaceMesh m = submap_face(l, top, loop, counts, dirs);
  EXPECT_FALSE(m.ok);
  ASSERT_FALSE(m.diagnostics.empty());
  EXPECT_EQ(m.diagnostics[0].code, "submap_failed");
}

}  // namespace
}  // namespace vorohex::mesh
