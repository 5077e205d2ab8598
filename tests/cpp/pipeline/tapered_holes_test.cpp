// Holes that widen: a countersunk hole (a cone above a through hole, as PartDesign's Hole
// makes it), cut at the cone's foot into a block with the straight hole and a slab with the
// conical one, both swept; a pocket with drafted walls, cut at its floor into a block
// (multiswept) and a slab with a tapered hole (swept). The slabs' layers, carried by affine
// maps from the small hole's face to the large one's, fold (the nodes by the small hole land
// in the large one); each layer as the one below deformed to its boundary does not
// (mesh::SweepOptions::smooth_layers). The cut is meshed once: both sweeps take it as their
// source, a sweep takes a multisweep's quads there as its source.
#include <gtest/gtest.h>

#include <string>

#include "fixtures/diagnostics.h"
#include "fixtures/machined.h"
#include "mesh/sweep.h"
#include "pipeline/generate_mesh.h"
#include "quality/check_mesh.h"

namespace vorohex::pipeline {
namespace {

// Before, the grid mesher's (1,300 hexahedra, min 0.50, 6.7 s in bench/results/parts.md):
// the slab's sweep folded and the two sweeps' meshes of the cut did not match.
TEST(GenerateMesh, ABlockWithACountersunkHoleIsCutAtTheConesFootAndSwept) {
  const occ::Solid block = testing::make_block_with_countersunk_hole();
  MeshOptions opt;
  opt.fallback = false;
  const MeshResult r = generate_mesh(block, opt);
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  EXPECT_EQ(r.stats.sub_volumes, 2);
  EXPECT_EQ(r.stats.scheme, "sweep");
  const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "decomposed");
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find("the plane across the foot of Face"), std::string::npos) << d->message;
  EXPECT_TRUE(r.check.valid);
  EXPECT_GE(r.check.scaled_jacobian.min, 0.45);
  EXPECT_EQ(r.check.open_boundary_edges, 0u);
  EXPECT_LE(r.check.volume_rel_error, 0.01);
}

// Before, the grid mesher's (7.3 s): the planes of the drafted walls cut wedges off the block.
TEST(GenerateMesh, ABlockWithADraftedPocketIsCutAtItsFloorAndSwept) {
  const occ::Solid block = testing::make_block_with_drafted_pocket();
  MeshOptions opt;
  opt.fallback = false;
  const MeshResult r = generate_mesh(block, opt);
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  EXPECT_EQ(r.stats.sub_volumes, 2);
  EXPECT_EQ(r.stats.scheme, "sweep+multisweep");
  EXPECT_TRUE(r.check.valid);
  EXPECT_GE(r.check.scaled_jacobian.min, 0.45);
  EXPECT_EQ(r.check.open_boundary_edges, 0u);
  EXPECT_LE(r.check.volume_rel_error, 0.01);
}

TEST(Sweep, LayersSmoothedWithinTheirBoundaryDoNotFoldThroughAConicalHole) {
  const occ::Solid slab = testing::make_slab_with_conical_hole();
  mesh::SweepOptions o;
  o.size = 1.5;
  const mesh::SweepResult affine = mesh::sweep(slab, o);
  ASSERT_TRUE(affine.source.valid());
  // Swept from the small hole's face (the larger source) to the large hole's: folded.
  EXPECT_GT(affine.folded, 0u);
  EXPECT_FALSE(affine.ok);
  o.smooth_layers = true;
  const mesh::SweepResult smoothed = mesh::sweep(slab, o);
  ASSERT_TRUE(smoothed.ok) << (smoothed.diagnostics.empty()
                                   ? ""
                                   : core::format(smoothed.diagnostics.back()));
  EXPECT_EQ(smoothed.folded, 0u);
  EXPECT_EQ(smoothed.source, affine.source);
  const quality::CheckReport c = quality::check_mesh(smoothed.mesh, &slab);
  EXPECT_TRUE(c.valid);
  EXPECT_GT(c.scaled_jacobian.min, 0.3);
  // Every node of the target's inside is on the target face (its plane z = 4).
  for (std::size_t i = 0; i < smoothed.mesh.num_nodes(); ++i) {
    const core::NodeClass k = smoothed.mesh.node_classes()[i];
    if (k.dim == 2 && k.id == smoothed.target.value())
      EXPECT_NEAR(smoothed.mesh.points()[i].z(), 4.0, 1e-9);
  }
}

}  // namespace
}  // namespace vorohex::pipeline
