#include "mesh/submap_face.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fixtures/machined.h"
#include "fixtures/solids.h"
#include "mesh/face_set.h"
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

int count_type(const SubmapStructure& s, VertexType t) {
  int n = 0;
  for (const auto& w : s.types) n += int(std::count(w.begin(), w.end(), t));
  return n;
}

// Vertex types of rectilinear outlines: an L has five End vertices and one Corner; T, U
// and a three-step staircase six Ends and two Corners (Ends minus Corners is always 4).
TEST(SubmapFace, VertexTypesOfLTUAndStepped) {
  struct Case {
    const char* name;
    occ::Solid solid;
    int ends, corners;
  };
  std::vector<Case> cases;
  cases.push_back({"L", testing::make_l(3), 5, 1});
  cases.push_back({"T", testing::make_t(), 6, 2});
  cases.push_back({"U", testing::make_u(), 6, 2});
  cases.push_back(
      {"stepped",
       occ::make_prism({{0, 0}, {3, 0}, {3, 1}, {2, 1}, {2, 2}, {1, 2}, {1, 3}, {0, 3}}, 1), 6, 2});
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const SubmapStructure st = submap_structure(c.solid, top_face(c.solid));
    ASSERT_TRUE(st.ok) << st.reason;
    EXPECT_EQ(count_type(st, VertexType::end), c.ends);
    EXPECT_EQ(count_type(st, VertexType::corner), c.corners);
    EXPECT_EQ(count_type(st, VertexType::side), 0);
    // Meshed as a face set (all faces of the prism, shared edges), the outline is a lattice
    // of rectangles.
    FaceSetOptions o;
    o.size = 0.25;
    const FaceSetMesh m = mesh_face_set(c.solid, o);
    ASSERT_TRUE(m.ok) << (m.diagnostics.empty() ? "" : core::format(m.diagnostics[0]));
    EXPECT_EQ(m.face_schemes[top_face(c.solid).value()], "submap");
    EXPECT_NEAR(m.min_quality, 1.0, 1e-9);
  }
}

// A face with holes: each loop balances on its own, the holes sit in the lattice where the
// face puts them, every quad a rectangle.
TEST(SubmapFace, FacesWithRectangularHoles) {
  const occ::Solid plate = testing::make_plate_with_square_holes();
  const core::FaceId top = top_face(plate);
  const SubmapStructure st = submap_structure(plate, top);
  ASSERT_TRUE(st.ok) << st.reason;
  ASSERT_EQ(st.directions.size(), 3u);
  EXPECT_EQ(count_type(st, VertexType::end), 4);     // the outer rectangle
  EXPECT_EQ(count_type(st, VertexType::corner), 8);  // the holes' corners, seen from the material
  FaceSetOptions o;
  o.size = 0.25;
  const FaceSetMesh m = mesh_face_set(plate, o);
  ASSERT_TRUE(m.ok) << (m.diagnostics.empty() ? "" : core::format(m.diagnostics[0]));
  EXPECT_EQ(m.face_schemes[top.value()], "submap");
  EXPECT_NEAR(m.min_quality, 1.0, 1e-9);
  // 8 x 4 minus two 2 x 2 holes, in cells of 0.25: 32 x 16 - 2 x 8 x 8.
  EXPECT_EQ(m.quads[top.value()].size(), 32u * 16u - 2u * 64u);
}

// A rectangle with a vertex on one side (where a neighbour's edge ends: a lug's foot on a
// plate) is a mapped face whose side is a chain of two edges: the transfinite grid, whose
// nodes a neighbour meshing the same wall as a tensor product also has.
TEST(FaceSet, ARectangleWithAVertexOnASideIsMappedWithChainedSides) {
  const occ::Solid prism = occ::make_prism({{0, 0}, {4, 0}, {4, 2}, {1, 2}, {0, 2}}, 1);
  const core::FaceId top = top_face(prism);
  FaceSetOptions o;
  o.size = 0.5;
  const FaceSetMesh m = mesh_face_set(prism, o);
  ASSERT_TRUE(m.ok) << (m.diagnostics.empty() ? "" : core::format(m.diagnostics[0]));
  EXPECT_EQ(m.face_schemes[top.value()], "map");
  // 8 x 4 cells of 0.5: the chain 1 + 3 long takes 2 + 6 segments, the grid is square.
  EXPECT_EQ(m.quads[top.value()].size(), 32u);
  EXPECT_NEAR(m.min_quality, 1.0, 1e-9);
}

// Corners of exactly 45 and 135 degrees (a quarter disc parted along its diagonal, where a
// ball's octant is parted like a cube's corner) are corners of a mapped face, whichever side
// of 45 degrees rounding puts the turn: mapped alike, the neighbour's mapped face matches it.
TEST(FaceSet, CornersOfExactly45And135DegreesAreMapped) {
  int k = 0;
  for (const double w : {1.0, 0.635085296108588, 1.3})
    for (const double degrees : {0.0, 17.0, 30.0, 45.0, 60.0, 135.0}) {
      // The quadrilateral (0, 0) (3w, 0) (3w, w) (w, w) turned about the origin and moved.
      const double c = std::cos(degrees * testing::kPi / 180),
                   sn = std::sin(degrees * testing::kPi / 180);
      std::vector<std::array<double, 2>> outline;
      for (const auto& [x, y] :
           std::vector<std::array<double, 2>>{{0, 0}, {3 * w, 0}, {3 * w, w}, {w, w}})
        outline.push_back({1.365 + c * x - sn * y, 18.635 + sn * x + c * y});
      const occ::Solid prism = occ::make_prism(outline, 1);
      const core::FaceId top = top_face(prism);
      FaceSetOptions o;
      o.size = 0.25 * w;
      const FaceSetMesh m = mesh_face_set(prism, o);
      ASSERT_TRUE(m.ok) << (m.diagnostics.empty() ? "" : core::format(m.diagnostics[0]));
      EXPECT_EQ(m.face_schemes[top.value()], "map") << w << " turned by " << degrees;
      ++k;
    }
  EXPECT_EQ(k, 18);
}

// A Reversal vertex: the tip of a thin wedge-shaped slit into a square (interior angle
// about 354 degrees); the lattice splits along the slit and the mesh stays positive.
TEST(SubmapFace, ReversalVertexAtTheTipOfASlit) {
  const occ::Solid slit =
      occ::make_prism({{0, 0}, {1.9, 0}, {2, 2}, {2.1, 0}, {4, 0}, {4, 4}, {0, 4}}, 1);
  const core::FaceId top = top_face(slit);
  const SubmapStructure st = submap_structure(slit, top);
  ASSERT_TRUE(st.ok) << st.reason;
  EXPECT_EQ(count_type(st, VertexType::reversal), 1);
  EXPECT_EQ(count_type(st, VertexType::end), 6);
  double reversal_angle = 0;
  for (std::size_t k = 0; k < st.types[0].size(); ++k)
    if (st.types[0][k] == VertexType::reversal) reversal_angle = st.angles[0][k];
  EXPECT_NEAR(reversal_angle, 360 - 2 * std::atan(0.05) * 180 / testing::kPi, 1e-6);
  FaceSetOptions o;
  o.size = 0.25;
  const FaceSetMesh m = mesh_face_set(slit, o);
  ASSERT_TRUE(m.ok) << (m.diagnostics.empty() ? "" : core::format(m.diagnostics[0]));
  EXPECT_EQ(m.face_schemes[top.value()], "submap");
  EXPECT_GT(m.min_quality, 0.5);
}

// A curved face: the outer cylinder of a ring sector with a step cut out of its corner is
// an L in (angle, height); its lattice lies on the cylinder.
TEST(SubmapFace, CurvedLShapedFace) {
  const occ::Solid ring = occ::make_ring_sector(2, 3, 1.5, 2);
  const occ::Solid notched = testing::cut(ring, occ::make_box(2.5, 2, 2, {1.5, -1, 1}));
  core::FaceId outer;
  for (core::FaceId f : notched.faces()) {
    const core::Vec3 p =
        notched.vertex_point(notched.edge_first_vertex(notched.face_wires(f)[0][0].edge));
    if (!notched.face_is_planar(f) && std::abs(std::hypot(p.x(), p.y()) - 3) < 1e-9) outer = f;
  }
  ASSERT_TRUE(outer.valid());
  const SubmapStructure st = submap_structure(notched, outer);
  ASSERT_TRUE(st.ok) << st.reason;
  EXPECT_EQ(count_type(st, VertexType::corner), 1);
  FaceSetOptions o;
  o.size = 0.2;
  const FaceSetMesh m = mesh_face_set(notched, o);
  ASSERT_TRUE(m.ok) << (m.diagnostics.empty() ? "" : core::format(m.diagnostics[0]));
  EXPECT_EQ(m.face_schemes[outer.value()], "submap");
  EXPECT_GT(m.min_quality, 0.5);
  for (std::size_t n = 0; n < m.points.size(); ++n)
    if (m.on[n].dim == 2 && m.on[n].id == outer.value()) {
      EXPECT_NEAR(std::hypot(m.points[n].x(), m.points[n].y()), 3, 1e-9);
    }
}

// A face that is not submappable says which vertex and which angle.
TEST(SubmapFace, RefusalNamesTheVertexAndItsAngle) {
  std::vector<std::array<double, 2>> hexagon;
  for (int k = 0; k < 6; ++k)
    hexagon.push_back({std::cos(testing::kPi / 3 * k), std::sin(testing::kPi / 3 * k)});
  const occ::Solid prism = occ::make_prism(hexagon, 1);
  const SubmapStructure st = submap_structure(prism, top_face(prism));
  EXPECT_FALSE(st.ok);
  EXPECT_NE(st.reason.find("interior angle of 120 degrees"), std::string::npos) << st.reason;
  EXPECT_NE(st.reason.find("Vertex"), std::string::npos) << st.reason;
  // A disc (one edge, one Side vertex) turns by 0, not 360.
  const occ::Solid cylinder = occ::make_cylinder(1, 1);
  const SubmapStructure disc = submap_structure(cylinder, top_face(cylinder));
  EXPECT_FALSE(disc.ok);
  EXPECT_NE(disc.reason.find("turns by 0 degrees"), std::string::npos) << disc.reason;
}

}  // namespace
}  // namespace vorohex::mesh
