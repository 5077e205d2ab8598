// Parts with a hole across their main direction, meshed structured by the plane cuts'
// planes around the hole (decompose/detail/hole_planes.h).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

#include "fixtures/diagnostics.h"
#include "fixtures/machined.h"
#include "pipeline/generate_mesh.h"

namespace vorohex::pipeline {
namespace {

// A thin-walled tube with a cross hole (wall 1 of radius 20). Before the planes around its
// hole, no structured scheme took it and the grid mesher made 482,910 hexahedra at min
// scaled Jacobian 0.186 in 31 s (at diagonal / 25 its mesh was invalid).
TEST(GenerateMesh, AThinTubeWithACrossHoleIsCutAroundTheHoleAndMeshedStructured) {
  const occ::Solid tube = testing::make_thin_tube_with_cross_hole();
  for (const double divisions : {20.0, 25.0}) {
    SCOPED_TRACE(divisions);
    MeshOptions opt;
    opt.size = tube.diagonal() / divisions;
    opt.fallback = false;
    const MeshResult r = generate_mesh(tube, opt);
    ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
    EXPECT_GE(r.stats.sub_volumes, 2);
    for (const std::string& s : r.stats.sub_volume_schemes)
      EXPECT_TRUE(s == "map" || s == "sweep" || s == "multisweep") << s;
    const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "decomposed");
    ASSERT_NE(d, nullptr);
    EXPECT_EQ(
        d->message.rfind("Cut along planes around its holes (4 planes around the hole of ", 0), 0u)
        << d->message;
    EXPECT_TRUE(r.check.valid);
    EXPECT_GE(r.check.scaled_jacobian.min, 0.3);
    EXPECT_LT(r.mesh.num_hexes(), 5000u);
    EXPECT_EQ(r.check.open_boundary_edges, 0u);
    EXPECT_EQ(r.check.boundary_quads + 2 * r.check.interior_quads, 6 * r.mesh.num_hexes());
    EXPECT_LE(std::abs(r.check.mesh_volume - tube.volume()), r.check.volume_allowance);
  }
}

// What a user gets on the other parts with a cross hole the grid meshed before (a thicker
// tube: 172,008 hexahedra at 0.480 in 12 s; the block with a boss beside its hole: 5,968 at
// 0.500): the planes around the hole give sub-volumes that all sweep, and pieces with the
// hole's faces are not merged (merged, the tube's half with the hole through its wall was a
// sweep whose layers folded).
TEST(GenerateMesh, ATubeAndABlockWithACrossHoleAreMeshedStructured) {
  const std::pair<const char*, occ::Solid> parts[] = {
      {"tube", testing::make_tube_with_cross_hole()},
      {"block with a boss", testing::make_block_with_boss_and_cross_hole()}};
  for (const auto& [name, part] : parts) {
    SCOPED_TRACE(name);
    MeshOptions opt;
    opt.fallback = false;
    const MeshResult r = generate_mesh(part, opt);
    ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
    EXPECT_GE(r.stats.sub_volumes, 2);
    const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "decomposed");
    ASSERT_NE(d, nullptr);
    EXPECT_NE(d->message.find("planes around its holes"), std::string::npos) << d->message;
    EXPECT_TRUE(r.check.valid);
    EXPECT_GE(r.check.scaled_jacobian.min, 0.3);
    EXPECT_LT(r.mesh.num_hexes(), 5000u);
    EXPECT_LE(std::abs(r.check.mesh_volume - part.volume()), r.check.volume_allowance);
  }
}

// A flanged pipe with a cross hole, at diagonal / 20 and / 25. At / 25 the hole's piece of
// the wall (a sweep from the outer cylinder to the bore) folded 2 hexahedra where its target
// nodes were the bore's points nearest their affine images; placed along the sweep's axis
// instead (mesh::SweepOptions::target_along_axis, tried where the layers fold) it does not
// (before: the grid's 146,855 hexahedra).
TEST(GenerateMesh, AFlangedPipeWithACrossHoleIsMeshedStructuredAtBothSizes) {
  const occ::Solid pipe = testing::make_flanged_pipe_with_cross_hole();
  for (const double divisions : {20.0, 25.0}) {
    SCOPED_TRACE(divisions);
    MeshOptions opt;
    opt.size = pipe.diagonal() / divisions;
    opt.fallback = false;
    const MeshResult r = generate_mesh(pipe, opt);
    ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
    EXPECT_GE(r.stats.sub_volumes, 2);
    EXPECT_TRUE(r.check.valid);
    EXPECT_GE(r.check.scaled_jacobian.min, 0.3);
    EXPECT_LT(r.mesh.num_hexes(), 5000u);
  }
}

}  // namespace
}  // namespace vorohex::pipeline
