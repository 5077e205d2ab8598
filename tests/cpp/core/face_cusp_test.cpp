#include "core/face_cusp.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "fixtures/machined.h"
#include "mesh/multisweep.h"
#include "mesh/quad_face.h"
#include "occ/prismatic.h"

namespace vorohex::core {
namespace {

// A boss whose outline is tangent to the plate's from inside (HexMe i11: a plate's rounded
// end tangent to the tube through it): the plate's top around the boss is a crescent that
// comes to a point where the two circles touch.
occ::Solid plate_with_tangent_boss() {
  return testing::fuse(occ::make_cylinder(20, 4, Vec3::Zero(), testing::kZ),
                       occ::make_cylinder(10, 12, Vec3(10, 0, 0), testing::kZ));
}

TEST(FaceCusp, FindsTheCornerWhereAFaceComesToAPoint) {
  const occ::Solid s = plate_with_tangent_boss();
  const std::string where = first_cusp(s);
  ASSERT_FALSE(where.empty());
  EXPECT_NE(where.find("meet tangentially"), std::string::npos) << where;
  // It is the plate's top (z = 4) around the boss, at the point (20, 0, 4).
  bool found = false;
  for (FaceId f : s.faces()) {
    if (face_cusp(s, f).empty()) continue;
    const BoundingBox b = s.face_bounding_box(f);
    EXPECT_NEAR(b.min.z(), 4, 1e-6) << entity_name(f);
    EXPECT_NEAR(b.max.z(), 4, 1e-6) << entity_name(f);
    found = true;
  }
  EXPECT_TRUE(found);
}

// The multisweep's cross-section is that crescent. Its nodes next to the point are spaced
// for a ladder of quads there (mesh/detail/sizing.cpp, cusp_ladder.h): it meshes, with the
// corner at the point open (before: the quad meshing failed at the point).
TEST(FaceCusp, TheMultisweepMeshesTheCrescentWithALadderAtThePoint) {
  const occ::Solid s = plate_with_tangent_boss();
  ASSERT_TRUE(occ::prismatic_structure(s).ok);
  for (double size : {2.0, 1.0, 3.0}) {
    mesh::MultisweepOptions o;
    o.size = size;
    const mesh::MultisweepResult r = mesh::multisweep(s, o);
    ASSERT_TRUE(r.ok) << size << ": " << (r.diagnostics.empty() ? "" : r.diagnostics[0].message);
    EXPECT_GT(r.region_min_quality, 0.02) << size;
  }
}

// Nodes along the outline twice as far apart as along the hole (the spacing the edges get
// without the point in mind, where the outline's segments are the longer) leave no quad at
// the point with a positive angle: the quad meshing fails, and its error names the point.
TEST(FaceCusp, AFailedQuadMeshingNamesThePoint) {
  const occ::Solid s = plate_with_tangent_boss();
  FaceId crescent;
  for (FaceId f : s.faces())
    if (!face_cusp(s, f).empty()) crescent = f;
  ASSERT_TRUE(crescent.valid());
  std::vector<std::vector<Vec3>> loops;
  for (const auto& wire : s.face_wires(crescent)) {
    std::vector<Vec3> loop;
    for (const auto& oe : wire) {
      const double spacing = s.edge_length(oe.edge) > 100 ? 2 : 1;  // the outline's, the hole's
      std::vector<Vec3> p =
          s.edge_points_by_length(oe.edge, 2 * int(s.edge_length(oe.edge) / (2 * spacing)));
      if (!oe.forward) std::reverse(p.begin(), p.end());
      loop.insert(loop.end(), p.begin(), p.end() - 1);
    }
    loops.push_back(loop);
  }
  mesh::QuadFaceOptions o;
  o.size = 2;
  const mesh::QuadFaceMesh m = mesh::quad_face(s, crescent, loops, o);
  ASSERT_FALSE(m.ok);
  ASSERT_FALSE(m.diagnostics.empty());
  const std::string& message = m.diagnostics.front().message;
  EXPECT_NE(message.find("Quad meshing of"), std::string::npos) << message;
  EXPECT_NE(message.find("comes to a point"), std::string::npos) << message;
  EXPECT_NE(message.find("meet tangentially"), std::string::npos) << message;
}

// Sharp corners, reflex corners, holes and tangent (smooth) joins are no points.
TEST(FaceCusp, MachinedPartsHaveNone) {
  using namespace testing;
  for (const occ::Solid& s :
       {make_stepped_extrusion(), make_stepped_plate_with_holes(), make_plate_with_boss_and_holes(),
        make_flanged_pipe(), make_l_bracket_with_holes(), make_plate_with_lug(),
        make_stepped_shaft(), make_pulley(), make_hex_wheel_with_rod(),
        occ::make_ring_sector(5, 10, 3, 4)})
    EXPECT_EQ(first_cusp(s), "");
  // A plate with a round end tangent to its straight sides: smooth joins, not points.
  const occ::Solid slot =
      fuse(occ::make_box(20, 10, 3, Vec3(0, -5, 0)), occ::make_cylinder(5, 3, Vec3(20, 0, 0), kZ));
  EXPECT_EQ(first_cusp(slot), "");
}

}  // namespace
}  // namespace vorohex::core
