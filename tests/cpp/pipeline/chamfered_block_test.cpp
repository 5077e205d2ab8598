// Blocks with chamfered edges, as Part's Chamfer makes them: convex, so the midpoint
// subdivision takes them whole, poorly (a block with its four top edges chamfered: min
// scaled Jacobian 0.07 before smoothing, 0.15 after); and with no concave edge, so the cuts
// at concave edges never touch them. Cut across the chamfers' foot, they are a block and a
// tapered slab (decompose/detail/foot_planes.h), and the mesher takes that instead.
#include <gtest/gtest.h>

#include <string>

#include "decompose/detail/foot_planes.h"
#include "decompose/plane_cuts.h"
#include "fixtures/diagnostics.h"
#include "fixtures/machined.h"
#include "mesh/midpoint.h"
#include "occ/shape_io.h"
#include "pipeline/generate_mesh.h"

namespace vorohex::pipeline {
namespace {

TEST(FootPlanes, AChamferedBlockIsCutAcrossItsChamfersFoot) {
  const occ::Solid block = testing::make_block_with_chamfered_top();
  // One plane along z (z = 17, at the four edges where chamfers meet walls) comes first;
  // along x and y two each (where the end chamfers meet the top), and others along the
  // chamfers' own normals.
  const auto sets = decompose::detail::foot_plane_sets(block);
  ASSERT_GE(sets.size(), 3u);
  ASSERT_EQ(sets[0].planes.size(), 1u);
  EXPECT_NEAR(std::abs(sets[0].axis.z()), 1, 1e-12);
  EXPECT_NEAR(std::abs(sets[0].planes[0].offset), 17, 1e-9);
  EXPECT_EQ(sets[0].planes[0].edges.size(), 4u);
  EXPECT_EQ(sets[1].planes.size(), 2u);
  // The midpoint subdivision is poor; the mesher's cut is two blocks.
  EXPECT_LT(mesh::midpoint_coarse_quality(block), mesh::kPoorMidpointQuality);
  const decompose::PlaneCutResult cut = decompose::cut_as_the_mesher(block, {});
  ASSERT_TRUE(cut.ok) << cut.why_not;
  EXPECT_EQ(cut.pieces.size(), 2u);
  EXPECT_EQ(decompose::cut_kind_text(cut),
            "planes across the feet of its tapered or rounded faces");
  ASSERT_EQ(cut.surfaces.size(), 1u);
  EXPECT_TRUE(cut.surfaces[0].at_foot);
  EXPECT_EQ(
      decompose::surface_text(cut.surfaces[0], false).rfind("the plane across the foot of Face", 0),
      0u);
}

// A block with its four top edges filleted (FreeCAD's makeFillet, radius 2): the fillets are
// cylinders across z bulging out of it; their feet on the walls (z = 8) give one plane, and
// their edges on the top (at its extent's end) none.
TEST(FootPlanes, AFilletedBlockIsCutAcrossItsFilletsFoot) {
  const occ::ReadResult in =
      occ::read_solid(std::string(VOROHEX_SOURCE_DIR) + "/tests/data/block_top_fillets.step");
  ASSERT_TRUE(in.ok());
  const auto sets = decompose::detail::foot_plane_sets(*in.solid);
  ASSERT_GE(sets.size(), 1u);
  EXPECT_NEAR(std::abs(sets[0].axis.z()), 1, 1e-12);
  ASSERT_EQ(sets[0].planes.size(), 1u);
  EXPECT_NEAR(std::abs(sets[0].planes[0].offset), 8, 1e-6);
  EXPECT_EQ(sets[0].planes[0].edges.size(), 4u);
  const decompose::PlaneCutResult cut = decompose::cut_as_the_mesher(*in.solid, {});
  ASSERT_TRUE(cut.ok) << cut.why_not;
  EXPECT_EQ(cut.pieces.size(), 2u);
  EXPECT_EQ(decompose::cut_kind_text(cut),
            "planes across the feet of its tapered or rounded faces");
}

TEST(GenerateMesh, AChamferedBlockIsABlockAndATaperedSlabNotAPoorMidpointSubdivision) {
  const occ::Solid block = testing::make_block_with_chamfered_top();
  MeshOptions opt;
  const MeshResult r = generate_mesh(block, opt);
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  EXPECT_EQ(r.stats.sub_volumes, 2);
  EXPECT_EQ(r.stats.scheme, "map");
  const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "midpoint_replaced");
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find("The midpoint subdivision's minimum scaled Jacobian is only 0.0"),
            std::string::npos)
      << d->message;
  EXPECT_TRUE(r.check.valid);
  EXPECT_GE(r.check.scaled_jacobian.min, 0.55);
  EXPECT_NEAR(r.check.mesh_volume, block.volume(), 1e-9 * block.volume());
  // Without the decomposition the midpoint subdivision is what there is, and it is taken.
  opt.decompose = false;
  const MeshResult whole = generate_mesh(block, opt);
  ASSERT_TRUE(whole.ok);
  EXPECT_EQ(whole.stats.scheme, "midpoint");
  EXPECT_TRUE(whole.check.valid);
}

}  // namespace
}  // namespace vorohex::pipeline
