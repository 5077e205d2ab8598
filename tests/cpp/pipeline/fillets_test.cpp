// Rounded edges, as FreeCAD's Fillet leaves them: a block with its four top edges filleted,
// and a plate with the top edge of its hole filleted, are cut across the fillets' feet (where
// they meet the walls, tangent to them) into a block and a slab whose fillets are its sides,
// each mapped or swept. Before, both were the grid mesher's (the block in 8 s: no scheme
// takes it whole, it has no concave edge, and its Voronoi graph's split did not return).
// A fillet at a pocket's floor (concave) has no foot on a wall: the cut along the floor
// would leave a knife edge. A boss's root fillet (a concave torus) is cut through its foot on
// the plate along the coaxial cylinder instead: the boss is revolved.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <thread>

#include "fixtures/diagnostics.h"
#include "fixtures/mesh_checks.h"
#include "occ/shape_io.h"
#include "pipeline/generate_mesh.h"

namespace vorohex::pipeline {
namespace {

using testing::mesh_test_file;

// A valid mesh of a decomposition into `pieces` sub-volumes (0: any number) whose schemes
// include `scheme`, conforming and closed, its volume within 1 %, at least `min`; its
// decomposition's text names `cut` where given.
void expect_decomposed(const MeshResult& r, const std::string& scheme, int pieces, double min,
                       const std::string& cut = "") {
  EXPECT_NE(r.stats.scheme.find(scheme), std::string::npos) << r.stats.scheme;
  if (pieces > 0) EXPECT_EQ(r.stats.sub_volumes, pieces);
  EXPECT_TRUE(r.check.valid);
  EXPECT_EQ(r.check.open_boundary_edges, 0u);
  EXPECT_LE(r.check.volume_rel_error, 0.01);
  EXPECT_GE(r.check.scaled_jacobian.min, min);
  if (cut.empty()) return;
  const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "decomposed");
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find(cut), std::string::npos) << d->message;
}

void expect_cut_at_the_foot_of_a_fillet(const MeshResult& r) {
  EXPECT_TRUE(r.check.valid);
  EXPECT_EQ(r.stats.sub_volumes, 2);
  EXPECT_EQ(r.check.open_boundary_edges, 0u);
  EXPECT_LE(r.check.volume_rel_error, 0.01);
  const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "decomposed");
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find("the plane across the foot of Face"), std::string::npos) << d->message;
}

// 30 x 20 x 10, its top edges filleted with radius 2 (tests/data/block_top_fillets.step, made
// by bench/run_parts.py): a block and a slab 2 thick with the four fillets as its sides, both
// mapped. Where the fillets meet the top face tangentially, the top face and the last layer
// across a fillet are two faces of one hexahedron nearly flat (0.314 at the default size,
// 0.209 at 1.5): a pillow layer under the boundary splits them (0.500 at both).
TEST(GenerateMesh, ABlockWithItsTopEdgesFilletedIsCutAtTheFilletsFootAndMapped) {
  for (double size : {0.0, 1.5}) {
    SCOPED_TRACE(size);
    const MeshResult r = mesh_test_file("block_top_fillets.step", size);
    ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
    EXPECT_EQ(r.stats.scheme, "map");
    expect_cut_at_the_foot_of_a_fillet(r);
    EXPECT_GE(r.check.scaled_jacobian.min, 0.45);
    EXPECT_GE(r.check.scaled_jacobian.mean, 0.9);
    const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "boundary_pillowed");
    ASSERT_NE(d, nullptr);
    EXPECT_NE(d->message.find("nearly flat across an edge"), std::string::npos) << d->message;
  }
}

// 30 x 20 x 10, its four top and four vertical edges filleted with radius 2
// (tests/data/block_top_vertical_fillets.step): each top corner is an octant of a ball (a
// sphere's three-sided patch and its pole). Cut across the fillets' feet along every axis at
// once, each corner is parted like a cube's corner into four blocks, and the fillets' strips
// beside it into three, so that their faces meet: 46 blocks, sweeps and multisweeps, not
// merged. Before, the grid mesher's (768 hexahedra at 0.501, after 6 s waiting for the
// Voronoi graph's split); at a finer size as well.
TEST(GenerateMesh, ABoxWithItsTopAndVerticalEdgesFilletedIsPartedAtItsCorners) {
  for (double size : {0.0, 1.0}) {
    SCOPED_TRACE(size);
    const MeshResult r = mesh_test_file("block_top_vertical_fillets.step", size);
    ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
    EXPECT_EQ(r.stats.scheme.find("grid"), std::string::npos) << r.stats.scheme;
    expect_decomposed(r, "map", 46, 0.6, "4 octants of a ball, as at a corner where three");
    // About the count the size asks for: one interval per part of a fillet's radius at the
    // default size (the grid: 768 at 0.501).
    if (size == 0.0) EXPECT_LE(r.mesh.num_hexes(), 1300u);
  }
}

// An L bracket as a new user built it in PartDesign (60 x 50, legs 6 thick, 40 deep, its inner
// edge filleted 4, two holes off the middle of its foot, one in its upright;
// tests/data/l_bracket_fillet_holes.step): it has no concave edge, the fillet is the concave
// feature. Cut across each leg where the fillet meets it (the planes through the fillet's
// axis and its feet, at right angles to it: no knife edge), a corner with the fillet and two
// legs with their holes, each swept. Before, the grid mesher's: 60,037 hexahedra (its first
// grid invalid, one three times finer).
TEST(GenerateMesh, AnLBracketsInnerFilletIsCutAcrossEachLegAtItsFeet) {
  const MeshResult r = mesh_test_file("l_bracket_fillet_holes.step");
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  EXPECT_EQ(r.stats.scheme, "sweep");
  expect_decomposed(r, "sweep", 3, 0.6, "the plane across the foot of Face");
  EXPECT_LE(r.mesh.num_hexes(), 600u);
}

// Second order: the pillow goes under the corners' mesh, and the mid-edge nodes are made
// again on the pillowed one.
TEST(GenerateMesh, ASecondOrderMeshIsPillowedUnderItsCorners) {
  const MeshResult r = mesh_test_file("block_top_fillets.step", 0, 2);
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  EXPECT_EQ(r.mesh.order(), 2);
  EXPECT_EQ(r.mesh.num_hexes(), 1592u);
  EXPECT_NE(testing::find_diagnostic(r.diagnostics, "boundary_pillowed"), nullptr);
  EXPECT_TRUE(r.check.valid);
  EXPECT_GE(r.check.scaled_jacobian.min, 0.45);
}

// Several solids in one file (a 30 x 20 x 5 block under the filleted one, sharing its bottom
// face; tests/data/block_and_filleted_block.step): meshed one by one and joined, then
// pillowed as one mesh (0.386 -> 0.5), conforming across the shared face.
TEST(GenerateMesh, SeveralSolidsJoinedArePillowedAsOneMesh) {
  const occ::ReadResult in = occ::read_solid(
      std::string(VOROHEX_SOURCE_DIR) + "/tests/data/block_and_filleted_block.step", [] {
        occ::ReadOptions o;
        o.several_solids = true;
        return o;
      }());
  ASSERT_TRUE(in.ok());
  ASSERT_EQ(in.solid->num_solids(), 2);
  MeshOptions opt;
  opt.fallback = false;
  const MeshResult r = generate_mesh(*in.solid, opt);
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  EXPECT_EQ(r.stats.sub_volumes, 2);
  EXPECT_NE(testing::find_diagnostic(r.diagnostics, "boundary_pillowed"), nullptr);
  EXPECT_TRUE(r.check.valid);
  EXPECT_EQ(r.check.open_boundary_edges, 0u);
  EXPECT_GE(r.check.scaled_jacobian.min, 0.45);
}

// Large fillets at a fine size: 40 x 20 x 10, top edges filleted at radius 5, size 1
// (tests/data/block_top_fillets_r5.step). Where two fillets meet the top face, all three
// tangent at its corner, the mapped slab's corner hexahedra reach 0.133 even pillowed: below
// 0.2, so the grid mesher's mesh made beside the decomposition is taken (0.5).
TEST(GenerateMesh, APoorDecompositionMeshGivesWayToTheFallbacksMadeBeside) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "no fallback beside on one core";
  const occ::ReadResult in =
      occ::read_solid(std::string(VOROHEX_SOURCE_DIR) + "/tests/data/block_top_fillets_r5.step");
  ASSERT_TRUE(in.ok());
  MeshOptions opt;
  opt.size = 1;
  const MeshResult r = generate_mesh(*in.solid, opt);
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  EXPECT_EQ(r.stats.scheme, "grid");
  const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "structured_replaced");
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find("below 0.2"), std::string::npos) << d->message;
  // Why the grid: said in its fallback warning, and the decomposition's cut is still named.
  EXPECT_NE(testing::find_diagnostic(r.diagnostics, "decomposed"), nullptr);
  EXPECT_TRUE(r.check.valid);
  EXPECT_GE(r.check.scaled_jacobian.min, 0.45);
  // At the default size (2.5) the same block stays structured (0.5, pillowed).
  const MeshResult coarse = generate_mesh(*in.solid, MeshOptions{});
  ASSERT_TRUE(coarse.ok);
  EXPECT_EQ(coarse.stats.scheme, "map");
  EXPECT_EQ(testing::find_diagnostic(coarse.diagnostics, "structured_replaced"), nullptr);
}

// Chamfers and fillets on one part (40 x 20 x 10 with a hole; its long top edges chamfered
// 1.5, its short ones and the hole's filleted 1; tests/data/block_chamfered_and_filleted.step):
// the feet at two heights cut a block and two slabs, three sweeps stacked, each slab's source
// the target of the one below, meshed freely (the hole). Each takes the quads of the one below
// there as its source, so they conform. Before, each meshed its own and the join failed
// (non_conforming_interface): the grid's 16,040 hexahedra.
TEST(GenerateMesh, StackedSweepsTakeTheQuadsOfTheOneBelowAsTheirSource) {
  const MeshResult r = mesh_test_file("block_chamfered_and_filleted.step");
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  EXPECT_EQ(r.stats.scheme, "sweep");
  expect_decomposed(r, "sweep", 3, 0.5);
}

// The pillowed mesh is used only where it is better: on the plate its sweep is good as it is.
TEST(GenerateMesh, AGoodStructuredMeshIsNotPillowed) {
  const MeshResult r = mesh_test_file("plate_hole_edge_fillet.step", 1.5);
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  EXPECT_EQ(testing::find_diagnostic(r.diagnostics, "boundary_pillowed"), nullptr);
  EXPECT_EQ(testing::find_diagnostic(r.diagnostics, "boundary_pillow_failed"), nullptr);
}

// 40 x 30 x 8 with a hole of radius 5, the hole's top edge filleted with radius 1.5 (a torus
// about the hole's axis; tests/data/plate_hole_edge_fillet.step): a plate and a slab whose
// hole flares out, both swept.
TEST(GenerateMesh, APlateWithItsHolesEdgeFilletedIsCutAtTheFilletsFootAndSwept) {
  const MeshResult r = mesh_test_file("plate_hole_edge_fillet.step");
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  EXPECT_EQ(r.stats.scheme, "sweep");
  expect_cut_at_the_foot_of_a_fillet(r);
  EXPECT_GE(r.check.scaled_jacobian.min, 0.45);
}

// 60 x 40 x 10 with a boss of radius 8 and height 15, its root filleted with radius 2 and
// the plate's two short top edges too (FreeCAD's Fillet; tests/data/plate_boss_root_fillet.step).
// It has no concave edge: the grid mesher's before (29,664 hexahedra, 7 s). Cut across the
// plate fillets' feet and along the cylinder through the root fillet's foot: a block and a
// slab with a round hole, swept, and the boss with its fillet, revolved.
TEST(GenerateMesh, ABossWithItsRootFilletedIsCutAtTheFilletsFootAndRevolved) {
  const MeshResult r = mesh_test_file("plate_boss_root_fillet.step");
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  EXPECT_EQ(r.stats.scheme, "sweep+revolve");
  expect_decomposed(r, "revolve", 3, 0.45, "the cylinder through the foot of Face");
  const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "decomposed");
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find("1 revolved"), std::string::npos) << d->message;
}

// The same boss with its root chamfered by 2 instead (a cone meeting the plate at a concave
// edge; tests/data/plate_boss_root_chamfer.step): the plate's top extended cuts the boss off
// with its cone, a solid of revolution no sweep takes, over a block whose cap its circle
// splits; cut through the chamfer's foot too, a sweep and the revolved boss. Before, the
// grid's: 29,752 hexahedra in 4.5 s.
TEST(GenerateMesh, ABossWithItsRootChamferedIsCutAtTheChamfersFootAndRevolved) {
  const MeshResult r = mesh_test_file("plate_boss_root_chamfer.step");
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  EXPECT_EQ(r.stats.scheme, "sweep+revolve");
  expect_decomposed(r, "revolve", 2, 0.5);
}

// A 60 x 40 x 20 block with a round pocket of radius 10, its floor filleted by 2
// (tests/data/round_pocket_floor_fillet.step): cut through the fillet's foot on the floor and
// along a cylinder as far beyond the wall, the column under the floor and the block outside
// are swept and the ring between them, with the fillet and the pocket's wall, revolved. Before,
// the grid's: 890 hexahedra at min 0.284 in 6.4 s.
TEST(GenerateMesh, ARoundPocketWithItsFloorFilletedHasItsFilletOnARevolvedRing) {
  const MeshResult r = mesh_test_file("round_pocket_floor_fillet.step");
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  expect_decomposed(r, "revolve", 3, 0.45, "a cylinder around the pocket rounded by Face");
}

// The same pocket in second order (FreeCAD's panel asks for it by default): at the automatic
// size one element spans the fillet across the ring, and the mid-edge nodes put on the fillet
// fold it; they are put back straight, off the CAD, and the mesh was invalid (nodes_off_cad).
// Made again at half the size, it is valid, and says so.
TEST(GenerateMesh, ASecondOrderMeshOffTheCadIsMadeAgainAtHalfTheSize) {
  const MeshResult r = mesh_test_file("round_pocket_floor_fillet.step", 0, 2);
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  expect_decomposed(r, "revolve", 3, 0.45);
  const core::Diagnostic* d =
      testing::find_diagnostic(r.diagnostics, "size_reduced_for_second_order");
  ASSERT_NE(d, nullptr);
  EXPECT_LT(r.stats.size_used, 0.51 * 3.7417);
  EXPECT_EQ(testing::find_diagnostic(r.diagnostics, "nodes_off_cad"), nullptr);
}

// A plate 80 x 40 x 12 with a boss of radius 8 whose root is filleted by 2 and a pocket
// 20 x 20 x 6 beside it (tests/data/plate_boss_root_fillet_and_pocket.step): the plate around
// the boss is a multisweep (the pocket's floor is a level), meshed first; the revolved boss
// takes its nodes on the seam they share (a node at the pocket floor's height among them), and
// the circles they share are split into arcs where the pocket wall's plane touched the cut
// cylinder (a quarter of a turn apart: each arc its share of the sectors). Before, the grid's.
TEST(GenerateMesh, ARevolvedBossTakesTheNodesOfTheMultisweepBesideIt) {
  const MeshResult r = mesh_test_file("plate_boss_root_fillet_and_pocket.step");
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  expect_decomposed(r, "revolve", 2, 0.5);
  expect_decomposed(r, "multisweep", 2, 0.5);
}

// A plate 60 x 40 x 15 with a pocket 30 x 20 x 8, its floor edges filleted with radius 3 in
// FreeCAD's Fillet (tests/data/pocket_floor_fillet.step): each fillet on a strip between the
// plane across its foot and a plane as far beyond its wall, the strips meeting at the mitres
// of the pocket's corners: four sweeps from mitre to mitre (in a ring: the last one's target
// the first one's source) and blocks. Before, the grid's (4,510 hexahedra).
TEST(GenerateMesh, APocketWithItsFloorFilletedIsSweptAlongItsFilletsStrips) {
  const MeshResult r = mesh_test_file("pocket_floor_fillet.step");
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  expect_decomposed(r, "sweep", 21, 0.4,
                    "the strips of Face3, Face7, Face9 and Face14 (across their feet and as far "
                    "beyond their walls), ended at 4 mitre planes");
  expect_decomposed(r, "map", 21, 0.4);
  EXPECT_LT(r.mesh.num_hexes(), 1500u);
}

// A rectangular boss 24 x 12 x 8 whose root is filleted with radius 2, and a plate with two
// pockets whose floors are (tests/data/plate_rect_boss_root_fillet.step,
// two_pockets_floor_fillet.step; before, the grid's: 78,006 hexahedra for the two pockets).
TEST(GenerateMesh, ABossWithItsRootFilletedAndTwoPocketsAreSweptAlongTheirStrips) {
  for (const char* name : {"plate_rect_boss_root_fillet.step", "two_pockets_floor_fillet.step"}) {
    SCOPED_TRACE(name);
    const MeshResult r = mesh_test_file(name);
    ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
    expect_decomposed(r, "sweep", 0, 0.45, "mitre planes");
    EXPECT_LT(r.mesh.num_hexes(), 1500u);
  }
}

// The pocket with its vertical corners rounded by 5 too, and a rectangular boss whose vertical
// edges are rounded by 3 and its root by 2 (tests/data/pocket_rounded_corners_floor_fillet.step,
// plate_rounded_boss_root_fillet.step): the strips turn round the corners on quarter rings,
// each swept round the corner's axis; all ten sub-volumes are sweeps. Before, the grid's
// (the pocket: 4,530 hexahedra at 0.500).
TEST(GenerateMesh, RoundedCornersTurnTheFilletsStripsOnSweptQuarterRings) {
  const MeshResult r = mesh_test_file("pocket_rounded_corners_floor_fillet.step");
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  expect_decomposed(r, "sweep", 10, 0.6, "turning round 4 rounded corners");
  EXPECT_EQ(r.stats.scheme, "sweep");
  EXPECT_LT(r.mesh.num_hexes(), 1500u);
  const MeshResult b = mesh_test_file("plate_rounded_boss_root_fillet.step");
  ASSERT_TRUE(b.ok) << (b.diagnostics.empty() ? "" : core::format(b.diagnostics.back()));
  expect_decomposed(b, "sweep", 0, 0.45, "turning round 4 rounded corners");
}

// An L-shaped pocket (two boxes fused and refined, cut from a plate 60 x 50 x 15), its six floor
// edges filleted with radius 2 (tests/data/l_pocket_floor_fillet.step, made by
// bench/run_parts.py): six strips, the two at the L's inner corner meeting at a convex mitre.
// The inner corner's strips' planes run through the whole plate and cross the long sides'
// strips; the piece of a long side's strip between them counted as in both strips and was
// merged with the blocks beside it into a multisweep, and the long side's two halves, swept
// from the caps of two such multisweeps, did not match at their mitre: the grid's, 5,280
// hexahedra. A piece in two strips' planes but beside one's fillet only is in that strip only.
TEST(GenerateMesh, AnLShapedPocketsStripsMeetAtItsInnerCornerToo) {
  const MeshResult r = mesh_test_file("l_pocket_floor_fillet.step");
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  expect_decomposed(r, "sweep", 0, 0.45,
                    "the strips of Face3, Face6, Face9, Face16, Face17 and Face18 (across their "
                    "feet and as far beyond their walls), ended at 6 mitre planes");
  EXPECT_EQ(r.stats.scheme.find("multisweep"), std::string::npos) << r.stats.scheme;
  EXPECT_LT(r.mesh.num_hexes(), 1500u);
  // A T-shaped pocket the same way (tests/data/t_pocket_floor_fillet.step, bench/run_parts.py):
  // its cut leaves 71 pieces, the corners' halves without a scheme until merged; past 60
  // pieces a cut's pieces each needed a scheme before they were glued, so its strips were never
  // merged (the grid's, 5,476 hexahedra at 0.151). 43 blocks and sweeps.
  const MeshResult t = mesh_test_file("t_pocket_floor_fillet.step");
  ASSERT_TRUE(t.ok) << (t.diagnostics.empty() ? "" : core::format(t.diagnostics.back()));
  expect_decomposed(t, "sweep", 0, 0.45, "ended at 8 mitre planes");
  EXPECT_LT(t.mesh.num_hexes(), 1500u);
}

// The rectangular boss whose root is filleted (radius 2), its top edges filleted too (radius 1;
// tests/data/plate_rect_boss_root_top_fillets.step, made by bench/run_parts.py): the root's
// strips ended as far beyond the boss's walls as their feet are in front, 1 inside the top
// fillets' feet, leaving a sliver of the top face on each strip. Now a strip ends at an edge
// along it behind the wall between a quarter and one and a half times as far (the top
// fillet's foot), and a strip's end whose side turns round through the two fillets, where
// its lattice folds, is meshed by the quad mesher. Meshed structured at size 1.5; at the
// default size (3.7) and at 3 the quad mesher's mesh of a strip's end inverts a quad and the
// grid meshes it.
TEST(GenerateMesh, ABossWithItsRootAndTopEdgesFilletedIsSweptAlongItsRootsStrips) {
  const MeshResult r = mesh_test_file("plate_rect_boss_root_top_fillets.step", 1.5);
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  expect_decomposed(r, "sweep", 0, 0.45, "ended at 4 mitre planes");
}

}  // namespace
}  // namespace vorohex::pipeline
