// A solid of revolution among the sub-volumes: a plate with a boss whose root is filleted
// (FreeCAD's Fillet on the boss's root edge and on two of the plate's top edges;
// tests/data/plate_boss_root_fillet.step) has no concave edge. Cut through the fillet's foot on
// the plate along the coaxial cylinder, and across the feet of the plate's own fillets, it is
// a block, a slab with a round hole and the boss with its fillet: the last is revolved, its
// sectors starting at the vertex of the circles it shares, and its neighbours take its nodes
// on the seam they share, so the meshes conform.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "decompose/plane_cuts.h"
#include "fixtures/diagnostics.h"
#include "mesh/mesh_sub_volumes.h"
#include "occ/shape_io.h"
#include "quality/check_mesh.h"

namespace vorohex::mesh {
namespace {

using testing::messages;

TEST(RevolvedSubVolumes, ABossWithItsRootFilletedIsRevolvedBesideItsPlate) {
  const occ::ReadResult in =
      occ::read_solid(std::string(VOROHEX_SOURCE_DIR) + "/tests/data/plate_boss_root_fillet.step");
  ASSERT_TRUE(in.ok());
  const decompose::PlaneCutResult cut = decompose::cut_as_the_mesher(*in.solid, {});
  ASSERT_TRUE(cut.ok) << cut.why_not;
  // The plane across the plate's fillets' feet and the cylinder through the boss fillet's.
  ASSERT_EQ(cut.pieces.size(), 3u);
  bool cylinder_at_foot = false;
  for (const decompose::CutSurface& s : cut.surfaces)
    cylinder_at_foot = cylinder_at_foot || (s.used && s.cylinder && s.at_foot);
  EXPECT_TRUE(cylinder_at_foot);
  std::vector<const occ::Solid*> pieces;
  for (const occ::Solid& s : cut.pieces) pieces.push_back(&s);
  const occ::ReadResult glued = occ::glue_solids(pieces, "The pieces");
  ASSERT_TRUE(glued.ok()) << messages(glued.diagnostics);
  SubVolumeMeshOptions o;
  o.size = 3.8;
  const SubVolumeMeshResult r = mesh_sub_volumes(*glued.solid, o);
  ASSERT_TRUE(r.ok) << messages(r.diagnostics);
  std::vector<std::string> schemes = r.stats.schemes;
  std::sort(schemes.begin(), schemes.end());
  EXPECT_EQ(schemes, (std::vector<std::string>{"revolve", "sweep", "sweep"}));
  EXPECT_GT(r.stats.nodes_merged, 0u);
  // Conforming where they meet (the cylinder cut, the plane under the boss), closed, every
  // hexahedron positive, before any smoothing.
  const quality::CheckReport check = quality::check_mesh(r.mesh, glued.solid.get(), {});
  EXPECT_TRUE(check.valid) << messages(check.diagnostics);
  EXPECT_EQ(check.open_boundary_edges, 0u);
  EXPECT_GE(check.scaled_jacobian.min, 0.3);
}

}  // namespace
}  // namespace vorohex::mesh
