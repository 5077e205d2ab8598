// Issue 6's planar solids through the whole pipeline: valid meshes whose quality before
// smoothing meets the bar (min scaled Jacobian >= 0.3, mean >= 0.85), with the
// volume of the CAD to 1e-9.
#include "pipeline/generate_mesh.h"

#include <gtest/gtest.h>

#include "fixtures/diagnostics.h"
#include "fixtures/solids.h"
#include "occ/primitives.h"

namespace vorohex::pipeline {
namespace {

struct Named {
  const char* name;
  occ::Solid solid;
};

TEST(GenerateMesh, PlanarSolidsAreValidAndGoodBeforeSmoothing) {
  std::vector<Named> solids;
  solids.push_back({"box", occ::make_box(3, 2, 1)});
  solids.push_back({"cube", occ::make_box(1, 1, 1)});
  solids.push_back({"tapered brick", occ::make_tapered_brick(4, 2, 1.5, 0.4)});
  solids.push_back({"thick L", testing::make_l(3)});
  solids.push_back({"thin L", testing::make_l(0.4)});
  solids.push_back({"T", testing::make_t()});
  solids.push_back({"U", testing::make_u()});
  solids.push_back({"plate with square holes", testing::make_plate_with_square_holes()});
  solids.push_back({"stepped block", testing::make_stepped_block()});
  for (const Named& s : solids) {
    SCOPED_TRACE(s.name);
    MeshOptions opt;
    opt.size = 0.25;
    const MeshResult r = generate_mesh(s.solid, opt);
    ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics[0]));
    EXPECT_TRUE(r.check.valid);
    EXPECT_GT(r.check.scaled_jacobian.min, 0);
    EXPECT_GE(r.stats.min_sj_before_smoothing, 0.3);
    EXPECT_GE(r.stats.mean_sj_before_smoothing, 0.85);
    EXPECT_NEAR(r.check.mesh_volume, s.solid.volume(), 1e-9 * s.solid.volume());
    EXPECT_GT(r.mesh.num_hexes(), 0u);
  }
}

TEST(GenerateMesh, SolidsThatNeedSeveralSubVolumesAreRefusedWithTheirDecomposition) {
  const occ::Solid cut_cube = testing::make_cut_cube();
  MeshOptions opt;
  opt.size = 0.25;
  const MeshResult r = generate_mesh(cut_cube, opt);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.mesh.num_hexes(), 0u);
  const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "not_supported_yet");
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find("Not a block"), std::string::npos) << d->message;
  // The user learns where it would be cut (the cut cube: three blocks around the notch).
  EXPECT_NE(d->message.find("Its decomposition"), std::string::npos) << d->message;
  EXPECT_NE(d->message.find("sub-volumes"), std::string::npos) << d->message;
}

}  // namespace
}  // namespace vorohex::pipeline
