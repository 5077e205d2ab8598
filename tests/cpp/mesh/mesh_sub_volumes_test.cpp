// Meshing the sub-volumes of a decomposition into one mesh: the thick L, T and U cut
// (without merging) into blocks and sweeps by the real decomposition, glued, meshed with one
// interval assignment, joined, put back onto the original topology, and checked against the
// original solid. (The plate with square holes is not here: unmerged, its decomposition
// leaves one sweep whose source loops touch at the holes' corners, which the quad mesher
// refuses; merged it is one sweep.)
#include "mesh/mesh_sub_volumes.h"

#include <gtest/gtest.h>

#include <cmath>

#include "decompose/decompose.h"
#include "fixtures/diagnostics.h"
#include "fixtures/solids.h"
#include "mesh/sweep.h"
#include "occ/primitives.h"
#include "occ/shape_io.h"
#include "occ/split_solid.h"
#include "quality/check_mesh.h"
#include "smooth/restore_topology.h"
#include "voronoi/voronoi_graph.h"

namespace vorohex::mesh {
namespace {

using testing::messages;

struct Pieces {
  std::unique_ptr<occ::Solid> glued;
  std::size_t count = 0;
};

Pieces cut(const occ::Solid& solid) {
  const voronoi::VoronoiResult graph = voronoi::compute_voronoi_graph(solid);
  decompose::DecomposeOptions opt;
  opt.merge = false;
  const decompose::DecompositionResult d = decompose::decompose(solid, graph, opt);
  Pieces p;
  if (!d.ok()) {
    ADD_FAILURE() << "decomposition: " << messages(d.diagnostics);
    return p;
  }
  std::vector<const occ::Solid*> solids;
  for (const auto& sv : d.sub_volumes) solids.push_back(sv.solid.get());
  occ::ReadResult r = occ::glue_solids(solids, "The decomposition");
  if (!r.ok()) ADD_FAILURE() << "glue: " << messages(r.diagnostics);
  p.glued = std::move(r.solid);
  p.count = solids.size();
  return p;
}

struct Case {
  const char* name;
  occ::Solid solid;
  double size;
  std::size_t pieces;
};

TEST(MeshSubVolumes, DecomposedSolidsGiveOneConformingValidMesh) {
  std::vector<Case> cases;
  cases.push_back({"thick L", testing::make_l(3), 0.25, 3});
  cases.push_back({"T", testing::make_t(), 0.25, 4});
  cases.push_back({"U", testing::make_u(), 0.25, 5});
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const Pieces p = cut(c.solid);
    ASSERT_TRUE(p.glued) << c.name;
    EXPECT_EQ(p.count, c.pieces);
    ASSERT_EQ(p.glued->num_solids(), int(c.pieces));
    SubVolumeMeshOptions o;
    o.size = c.size;
    SubVolumeMeshResult r = mesh_sub_volumes(*p.glued, o);
    ASSERT_TRUE(r.ok) << messages(r.diagnostics);
    EXPECT_EQ(r.stats.schemes.size(), c.pieces);
    ASSERT_EQ(r.stats.types.size(), c.pieces);
    for (std::size_t k = 0; k < c.pieces; ++k)
      if (r.stats.schemes[k] == "map") {
        EXPECT_EQ(r.stats.types[k], "Ve");
      }
    EXPECT_GT(r.stats.nodes_merged, 0u);
    // Against the glued pieces: conforming, closed, every hex positive.
    const quality::CheckReport pieces_check = quality::check_mesh(r.mesh, p.glued.get(), {});
    EXPECT_TRUE(pieces_check.valid) << messages(pieces_check.diagnostics);
    // Back on the original topology: no node is left on a decomposition face, and the mesh
    // is valid against the original solid (volume within 1e-9, nodes on the CAD).
    const double tol = 1e-9 * c.solid.diagonal();
    const smooth::RestoreStats restored = smooth::restore_topology(r.mesh, *p.glued, c.solid, tol);
    EXPECT_GT(restored.interior, 0u);
    const quality::CheckReport check = quality::check_mesh(r.mesh, &c.solid, {});
    EXPECT_TRUE(check.valid) << messages(check.diagnostics);
    EXPECT_EQ(check.non_positive, 0u);
    EXPECT_GE(check.scaled_jacobian.min, 0.3);
    EXPECT_GE(check.scaled_jacobian.mean, 0.85);
    for (std::size_t i = 0; i < r.mesh.num_nodes(); ++i) {
      const core::NodeClass k = r.mesh.node_class(core::NodeId(std::int32_t(i)));
      const core::Vec3& x = r.mesh.point(core::NodeId(std::int32_t(i)));
      double d = 0;
      if (k.dim == 2) d = c.solid.distance_to_face(core::FaceId(k.id), x);
      if (k.dim == 1) d = c.solid.distance_to_edge(core::EdgeId(k.id), x);
      if (k.dim == 0) d = c.solid.distance_to_vertex(core::VertexId(k.id), x);
      EXPECT_LE(d, 1e-7) << "node " << i << " on entity of dimension " << k.dim;
    }
  }
}

// The plan judges each piece glued to the others: a plate with a hole is a sweep alone, but
// not once an upright standing on it splits its top face (the merged corner and base of an
// L bracket); the upright, whose foot is a four-sided linking face, still is. Without the
// multisweep the plate has no scheme; with it (the default) the plate is a multisweep and
// the two are meshed into one conforming mesh.
TEST(MeshSubVolumes, ThePlanJudgesPiecesGluedToTheirNeighbours) {
  const std::unique_ptr<occ::Solid> base =
      occ::cut_solids(occ::make_box(40, 30, 5), occ::make_cylinder(4, 20, {22, 15, -5}, {0, 0, 1}));
  const std::unique_ptr<occ::Solid> upright = occ::cut_solids(
      occ::make_box(5, 30, 25, {0, 0, 5}), occ::make_cylinder(4, 20, {-5, 15, 18}, {1, 0, 0}));
  ASSERT_TRUE(base && upright);
  EXPECT_TRUE(sweep_applicable(*base).ok);
  occ::ReadResult glued = occ::glue_solids({base.get(), upright.get()}, "The pieces");
  ASSERT_TRUE(glued.ok()) << messages(glued.diagnostics);
  const SubVolumePlan plan = plan_sub_volumes(*glued.solid, /*multisweep=*/false);
  EXPECT_FALSE(plan.ok);
  ASSERT_EQ(plan.schemes.size(), 2u);
  ASSERT_EQ(plan.reasons.size(), 2u);
  const int b = glued.solid->part(0).volume() > glued.solid->part(1).volume() ? 0 : 1;
  EXPECT_EQ(plan.schemes[b], "");
  EXPECT_NE(plan.reasons[b].find("once glued to its neighbours"), std::string::npos)
      << plan.reasons[b];
  EXPECT_EQ(plan.why_not, plan.reasons[b]);
  EXPECT_EQ(plan.schemes[1 - b], "sweep");
  EXPECT_EQ(plan.reasons[1 - b], "");
  // mesh_sub_volumes refuses it with the same reason.
  SubVolumeMeshOptions without;
  without.multisweep = false;
  const SubVolumeMeshResult r = mesh_sub_volumes(*glued.solid, without);
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_EQ(r.diagnostics.back().code, "no_scheme");

  // With the multisweep: the plate is one, meshed first; the upright's sweep meets its
  // counts on the shared edges, and the meshes conform on the foot.
  const SubVolumePlan with = plan_sub_volumes(*glued.solid);
  EXPECT_TRUE(with.ok) << with.why_not;
  ASSERT_EQ(with.schemes.size(), 2u);
  EXPECT_EQ(with.schemes[b], "multisweep");
  EXPECT_EQ(with.schemes[1 - b], "sweep");
  SubVolumeMeshOptions o;
  o.size = 2.5;
  const SubVolumeMeshResult m = mesh_sub_volumes(*glued.solid, o);
  ASSERT_TRUE(m.ok) << messages(m.diagnostics);
  EXPECT_EQ(m.stats.schemes[b], "multisweep");
  const quality::CheckReport check = quality::check_mesh(m.mesh, glued.solid.get());
  EXPECT_TRUE(check.valid) << messages(check.diagnostics);
  EXPECT_EQ(check.non_manifold_quads, 0u);
  EXPECT_EQ(check.open_boundary_edges, 0u);
  EXPECT_GE(check.scaled_jacobian.min, 0.3);
}

// The glued pieces meshed without multisweeps at `size`: one valid mesh, conforming and
// closed, at least `min`.
void expect_one_conforming_mesh(const occ::Solid& glued, double size, double min) {
  SubVolumeMeshOptions o;
  o.size = size;
  o.multisweep = false;
  const SubVolumeMeshResult m = mesh_sub_volumes(glued, o);
  ASSERT_TRUE(m.ok) << messages(m.diagnostics);
  const quality::CheckReport check = quality::check_mesh(m.mesh, &glued);
  EXPECT_TRUE(check.valid) << messages(check.diagnostics);
  EXPECT_EQ(check.non_manifold_quads, 0u);
  EXPECT_EQ(check.open_boundary_edges, 0u);
  EXPECT_GE(check.scaled_jacobian.min, min);
}

// Two coaxial cylinders stacked, their seams on opposite sides: gluing imprints each seam's
// vertex on the other's circle, so each lateral face has five edges, its far circle a chain
// of two arcs meeting at a side vertex. Each is still a sweep towards the shared disc (the
// chain's intervals sum to the circle's), and the meshes conform there.
TEST(MeshSubVolumes, ASweepTakesATargetSplitByItsNeighbour) {
  const occ::Solid lower = occ::make_cylinder(2, 3, {0, 0, 0}, {0, 0, 1});
  const occ::Solid upper = occ::make_cylinder(2, 3, {0, 0, 6}, {0, 0, -1});
  occ::ReadResult glued = occ::glue_solids({&lower, &upper}, "The pieces");
  ASSERT_TRUE(glued.ok()) << messages(glued.diagnostics);
  int five = 0;  // lateral faces whose wire has a chain of two arcs
  for (int k = 0; k < 2; ++k) {
    const occ::Solid& part = glued.solid->part(k);
    for (core::FaceId f : part.faces()) {
      const auto w = part.face_wires(f);
      five += w.size() == 1 && w[0].size() == 5;
    }
  }
  ASSERT_EQ(five, 2) << "the seams must not meet for this case";
  const SubVolumePlan plan = plan_sub_volumes(*glued.solid, /*multisweep=*/false);
  ASSERT_TRUE(plan.ok) << plan.why_not;
  EXPECT_EQ(plan.schemes, (std::vector<std::string>{"sweep", "sweep"}));
  expect_one_conforming_mesh(*glued.solid, 0.8, 0.3);
}

// A bar 3 long with two blocks on its side (split at x = 1.5) and two on its top (split at
// x = 1): glued, the bar's side and top are two faces each, and its bottom and other side carry
// the splits' vertices on their edges. No face of the bar is a source that four-sided faces
// join to one target, so no sweep without its neighbours' imprints takes it; with them it
// is a sweep along x whose linking sides are stacks of faces (their edges between on a layer)
// and chains of edges, and every piece conforms. (Stacks come only from gluing: such a sweep
// is meshed with its neighbours' intervals, never on its own.)
TEST(MeshSubVolumes, ASweepsLinkingSidesMayBeStacksOfFacesItsNeighboursSplit) {
  const occ::Solid bar = occ::make_box(3, 1, 1);
  const occ::Solid side0 = occ::make_box(1.5, 1, 1, {0, 1, 0});
  const occ::Solid side1 = occ::make_box(1.5, 1, 1, {1.5, 1, 0});
  const occ::Solid top0 = occ::make_box(1, 1, 1, {0, 0, 1});
  const occ::Solid top1 = occ::make_box(2, 1, 1, {1, 0, 1});
  occ::ReadResult glued = occ::glue_solids({&bar, &side0, &side1, &top0, &top1}, "The pieces");
  ASSERT_TRUE(glued.ok()) << messages(glued.diagnostics);
  int k = -1;  // the bar
  for (int i = 0; i < glued.solid->num_solids(); ++i)
    if (std::abs(glued.solid->part(i).volume() - 3) < 1e-9) k = i;
  ASSERT_GE(k, 0);
  const occ::Solid& part = glued.solid->part(k);
  EXPECT_FALSE(sweep_applicable(part).ok);
  const SweepStructure s = sweep_structure(part, {}, /*imprinted=*/true);
  ASSERT_TRUE(s.source.valid());
  EXPECT_EQ(s.levels.size(), 2u);  // the side's and the top's edges between their faces
  EXPECT_FALSE(plan_sub_volumes(*glued.solid, false).ok);
  const SubVolumePlan plan = plan_sub_volumes(*glued.solid, false, false, /*imprinted=*/true);
  ASSERT_TRUE(plan.ok) << plan.why_not;
  EXPECT_EQ(plan.schemes[std::size_t(k)], "sweep");
  expect_one_conforming_mesh(*glued.solid, 0.5, 0.9);
  // On its own (no intervals given) it says it needs its neighbours' intervals.
  SweepOptions alone;
  alone.size = 0.4;
  alone.imprinted = true;
  const SweepResult r = sweep(part, alone);
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_EQ(r.diagnostics[0].code, "intervals_needed");
}

// A decomposition's pieces written by `vorohex decompose -o` (tests/data), glued.
occ::ReadResult read_pieces(const std::string& name) {
  occ::ReadOptions ro;
  ro.several_solids = true;
  return occ::read_solid(std::string(VOROHEX_SOURCE_DIR) + "/tests/data/" + name, ro);
}

// A V-belt pulley with a keyway in its bore (bench/run_parts.py), as its plane cuts left it
// (42 pieces, as `vorohex decompose --auto -o` writes them:
// tests/data/vbelt_pulley_keyway_pieces.brep). The
// material over the keyway is a sweep between two multisweeps' walls: its source and target
// are faces the multisweeps meshed first (rows extruded), while its own submapped lattice
// there is smoothed (the same cells, inner nodes up to 1.2 apart). It takes their quads on
// both ends, paired by connectivity; before, the target's nearest-node pairing failed
// (target_mismatch) and, without it, the two meshes of each face did not match.
TEST(MeshSubVolumes, ASweepBetweenTwoMultisweepsTakesTheirQuadsOnBothEnds) {
  const occ::ReadResult in = read_pieces("vbelt_pulley_keyway_pieces.brep");
  ASSERT_TRUE(in.ok()) << messages(in.diagnostics);
  ASSERT_EQ(in.solid->num_solids(), 42);
  SubVolumeMeshOptions o;
  o.size = 5.78;  // the pulley's default (diagonal / 20)
  const SubVolumeMeshResult m = mesh_sub_volumes(*in.solid, o);
  ASSERT_TRUE(m.ok) << messages(m.diagnostics);
  int multisweeps = 0;
  for (const std::string& s : m.stats.schemes) multisweeps += s == "multisweep";
  EXPECT_GE(multisweeps, 2);
  const quality::CheckReport check = quality::check_mesh(m.mesh, in.solid.get());
  EXPECT_TRUE(check.valid) << messages(check.diagnostics);
  EXPECT_EQ(check.non_manifold_quads, 0u);
  EXPECT_EQ(check.open_boundary_edges, 0u);
  EXPECT_GT(check.scaled_jacobian.min, 0.2);
}

// A keyed shaft's plane-cut pieces where its careful merge pass stopped at 13
// (tests/data/keyed_shaft_pieces.brep): the 1-thick chamfer slab at its end is swept from the
// end face to the face it shares with the strip above, which that strip's sweep meshes as a
// linking side. Each meshed that face its own way (24 quads that did not match, and no error
// before the check); the slab now takes the strip's quads there as its target.
TEST(MeshSubVolumes, ASweepTakesTheQuadsOfAFaceItsNeighbourMeshesAsALinkingSide) {
  const occ::ReadResult in = read_pieces("keyed_shaft_pieces.brep");
  ASSERT_TRUE(in.ok()) << messages(in.diagnostics);
  ASSERT_EQ(in.solid->num_solids(), 13);
  SubVolumeMeshOptions o;
  o.size = 4.345;  // the shaft's default (diagonal / 20)
  const SubVolumeMeshResult m = mesh_sub_volumes(*in.solid, o);
  ASSERT_TRUE(m.ok) << messages(m.diagnostics);
  const quality::CheckReport check = quality::check_mesh(m.mesh, in.solid.get());
  EXPECT_TRUE(check.valid) << messages(check.diagnostics);
  EXPECT_EQ(check.open_boundary_edges, 0u);
  EXPECT_EQ(testing::find_diagnostic(check.diagnostics, "non_conforming_interface"), nullptr);
  EXPECT_GT(check.scaled_jacobian.min, 0.1);  // before smoothing (the pipeline's: 0.50)
}

}  // namespace
}  // namespace vorohex::mesh
