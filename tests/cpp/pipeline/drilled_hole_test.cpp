// Holes as PartDesign's Hole feature makes them: a blind hole ends in a drill point (a cone
// of 118 degrees). Its rim, where the hole's cylinder meets the cone, is a concave edge: the
// plane cuts cut along the cylinder, and the column under the hole is swept from its disc
// up to the cone.
#include <gtest/gtest.h>

#include <string>

#include "fixtures/diagnostics.h"
#include "fixtures/machined.h"
#include "pipeline/generate_mesh.h"

namespace vorohex::pipeline {
namespace {

// Before, the block with a drilled blind hole was the grid mesher's (1,371 hexahedra in
// 6.9 s, the Voronoi graph's split stopped at its time): the column's target, the cone,
// has an apex and a seam that no linking face reaches, and the sweep refused it.
TEST(GenerateMesh, ABlockWithADrilledBlindHoleIsCutAlongTheHoleAndSwept) {
  const occ::Solid block = testing::make_block_with_drilled_hole();
  MeshOptions opt;
  opt.fallback = false;
  const MeshResult r = generate_mesh(block, opt);
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  EXPECT_EQ(r.stats.sub_volumes, 2);
  EXPECT_EQ(r.stats.scheme, "sweep+multisweep");
  const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "decomposed");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->message.rfind("Cut along the faces at its concave edges (the cylinder of Face", 0),
            0u)
      << d->message;
  EXPECT_TRUE(r.check.valid);
  EXPECT_GE(r.check.scaled_jacobian.min, 0.4);
  EXPECT_EQ(r.check.open_boundary_edges, 0u);
  EXPECT_LE(r.check.volume_rel_error, 0.005);
}

}  // namespace
}  // namespace vorohex::pipeline
