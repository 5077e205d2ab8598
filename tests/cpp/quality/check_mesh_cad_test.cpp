// check_mesh against a CAD solid: node distances, classification and volume.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "fixtures/diagnostics.h"
#include "io/mesh_io.h"
#include "occ/primitives.h"
#include "quality/check_mesh.h"
#include "quality/grid_fixture.h"

namespace vorohex::quality {
namespace {

using core::HexMesh;
using core::NodeClass;
using core::NodeId;
using core::Vec3;
using testing::structured_grid;

const core::Diagnostic* find(const CheckReport& r, const std::string& code) {
  return vorohex::testing::find_diagnostic(r.diagnostics, code);
}

// Classifies every node on the lowest-dimensional entity it lies on, as a mesher would.
void classify_by_geometry(HexMesh& m, const occ::Solid& s, double tol = 1e-9) {
  for (std::size_t n = 0; n < m.num_nodes(); ++n) {
    const NodeId id(static_cast<std::int32_t>(n));
    const Vec3 p = m.point(id);
    NodeClass c = NodeClass::interior();
    for (core::VertexId v : s.vertices())
      if (c.is_interior() && s.distance_to_vertex(v, p) < tol) c = NodeClass::on(v);
    for (core::EdgeId e : s.edges())
      if (c.is_interior() && s.distance_to_edge(e, p) < tol) c = NodeClass::on(e);
    for (core::FaceId f : s.faces())
      if (c.is_interior() && s.distance_to_face(f, p) < tol) c = NodeClass::on(f);
    m.set_node_class(id, c);
  }
}

std::size_t grid_node(int nx, int ny, int i, int j, int k) {
  return i + (nx + 1) * (j + (ny + 1) * k);
}

TEST(CheckMeshCad, MatchingBoxGridIsValid) {
  const occ::Solid box = occ::make_box(3, 2, 1);
  HexMesh m = structured_grid(3, 2, 1);
  classify_by_geometry(m, box);
  EXPECT_EQ(m.node_class(NodeId(0)).dim, 0);
  EXPECT_EQ(m.node_class(NodeId(1)).dim, 1);                         // (1,0,0) on an edge
  EXPECT_EQ(m.node_class(NodeId(grid_node(3, 2, 1, 1, 0))).dim, 2);  // bottom face
  const CheckReport r = check_mesh(m, &box);
  EXPECT_TRUE(r.valid) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics[0]));
  EXPECT_TRUE(r.has_cad);
  EXPECT_NEAR(r.cad_volume, 6.0, 1e-9);
  EXPECT_NEAR(r.mesh_volume, 6.0, 1e-12);
  EXPECT_LT(r.volume_rel_error, 1e-9);
  EXPECT_LT(r.max_boundary_distance, 1e-9);
  EXPECT_NEAR(r.max_boundary_distance_rel, r.max_boundary_distance / std::sqrt(14.0), 1e-15);
  EXPECT_NEAR(r.volume_allowance, 6e-9, 1e-10);  // planar: no chord allowance
}

TEST(CheckMeshCad, UnclassifiedMeshIsMeasuredAgainstTheBoundary) {
  // Meshes from other tools carry no classification: all nodes count as interior.
  const occ::Solid box = occ::make_box(3, 2, 1);
  const CheckReport r = check_mesh(structured_grid(3, 2, 1), &box);
  EXPECT_TRUE(r.valid);
  EXPECT_LT(r.max_boundary_distance, 1e-9);
}

TEST(CheckMeshCad, DisplacedBoundaryNodeIsOffCad) {
  const occ::Solid box = occ::make_box(3, 2, 1);
  HexMesh m = structured_grid(3, 2, 1);
  classify_by_geometry(m, box);
  const NodeId top(static_cast<std::int32_t>(grid_node(3, 2, 1, 1, 1)));  // on the top face
  ASSERT_EQ(m.node_class(top).dim, 2);
  m.set_point(top, m.point(top) + Vec3(0, 0, 0.05));
  const CheckReport r = check_mesh(m, &box);
  EXPECT_FALSE(r.valid);
  const auto* d = find(r, "nodes_off_cad");
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find("nodes 17"), std::string::npos) << d->message;
  ASSERT_EQ(d->entities.size(), 1u);
  EXPECT_EQ(d->entities[0], core::entity_name(core::FaceId(m.node_class(top).id)));
  EXPECT_NEAR(r.max_boundary_distance, 0.05, 1e-9);
  // The raised node adds a bilinear tent over its four unit quads, each h/4: h in all.
  EXPECT_NEAR(r.mesh_volume - 6.0, 0.05, 1e-12);
  EXPECT_NE(find(r, "volume_mismatch"), nullptr);
}

TEST(CheckMeshCad, DisplacementWithinToleranceIsAccepted) {
  const occ::Solid box = occ::make_box(3, 2, 1);
  HexMesh m = structured_grid(3, 2, 1);
  classify_by_geometry(m, box);
  const NodeId top(static_cast<std::int32_t>(grid_node(3, 2, 1, 1, 1)));
  m.set_point(top, m.point(top) + Vec3(0, 0, 1e-8));  // 2.7e-9 of the diagonal
  const CheckReport r = check_mesh(m, &box);
  EXPECT_TRUE(r.valid) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics[0]));
  EXPECT_NEAR(r.max_boundary_distance, 1e-8, 1e-12);
}

TEST(CheckMeshCad, NodeIsMeasuredAgainstItsOwnEntity) {
  // Node 0 lies on the boundary but is classified on the face opposite to it.
  const occ::Solid box = occ::make_box(3, 2, 1);
  HexMesh m = structured_grid(3, 2, 1);
  classify_by_geometry(m, box);
  const NodeId on_top(static_cast<std::int32_t>(grid_node(3, 2, 1, 1, 1)));
  m.set_node_class(NodeId(0), m.node_class(on_top));  // the top face, 1 away
  const CheckReport r = check_mesh(m, &box);
  EXPECT_FALSE(r.valid);
  ASSERT_NE(find(r, "nodes_off_cad"), nullptr);
  EXPECT_NEAR(r.max_boundary_distance, 1.0, 1e-9);
}

TEST(CheckMeshCad, ClassificationOutsideTheSolidIsBad) {
  const occ::Solid box = occ::make_box(1, 1, 1);
  HexMesh m = structured_grid(1, 1, 1);
  classify_by_geometry(m, box);
  m.set_node_class(NodeId(3), NodeClass::on(core::FaceId(box.num_faces() + 1)));
  m.set_node_class(NodeId(4), NodeClass::on(core::EdgeId(box.num_edges() + 1)));
  const CheckReport r = check_mesh(m, &box);
  EXPECT_FALSE(r.valid);
  const auto* d = find(r, "bad_classification");
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find("nodes 3, 4"), std::string::npos) << d->message;
  // Badly classified boundary nodes are still measured (against the whole boundary).
  EXPECT_EQ(find(r, "nodes_off_cad"), nullptr);
}

TEST(CheckMeshCad, CavityIsClosedButMissesVolume) {
  const occ::Solid box = occ::make_box(3, 3, 3);
  const HexMesh full = structured_grid(3, 3, 3);
  HexMesh m;
  for (const Vec3& p : full.points()) m.add_node(p);
  for (std::size_t h = 0; h < full.num_hexes(); ++h)
    if (h != 13) m.add_hex(full.hexes()[h]);
  classify_by_geometry(m, box);
  const CheckReport r = check_mesh(m, &box);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.open_boundary_edges, 0u);
  EXPECT_NEAR(r.mesh_volume, 26.0, 1e-12);
  EXPECT_NEAR(r.cad_volume, 27.0, 1e-9);
  EXPECT_NEAR(r.volume_rel_error, 1.0 / 27.0, 1e-9);
  const auto* v = find(r, "volume_mismatch");
  ASSERT_NE(v, nullptr);
  EXPECT_NE(v->message.find("26"), std::string::npos) << v->message;
  EXPECT_NE(v->message.find("27"), std::string::npos) << v->message;
  // The cavity's nodes are 1 away from the box.
  ASSERT_NE(find(r, "nodes_off_cad"), nullptr);
  EXPECT_NEAR(r.max_boundary_distance, 1.0, 1e-9);
}

// A 3 x 3 x 1 plate meshed with a hole through its middle cell: every node lies on the CAD,
// the boundary is closed, but the hole's lining quads have two nodes on the bottom face and
// two on the top, faces that do not meet: they bridge the solid and are no chords of its
// surface. Their allowance (area times their centres' distance, 0.5 each) excused the
// missing ninth twice over, as a grid mesh that lost the material under a blind pocket's
// floor was valid; now it is volume_mismatch.
TEST(CheckMeshCad, QuadsBridgingFacesThatDoNotMeetGetNoChordAllowance) {
  const occ::Solid plate = occ::make_box(3, 3, 1);
  const HexMesh full = structured_grid(3, 3, 1);
  HexMesh m;
  for (const Vec3& p : full.points()) m.add_node(p);
  for (std::size_t h = 0; h < full.num_hexes(); ++h)
    if (h != 4) m.add_hex(full.hexes()[h]);
  classify_by_geometry(m, plate);
  const CheckReport r = check_mesh(m, &plate);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.open_boundary_edges, 0u);
  EXPECT_LT(r.max_boundary_distance, 1e-9);
  EXPECT_NEAR(r.volume_rel_error, 1.0 / 9.0, 1e-9);
  EXPECT_LT(r.volume_allowance, 1e-6);
  EXPECT_NE(find(r, "volume_mismatch"), nullptr);
}

TEST(CheckMeshCad, UnmergedBlocksHaveNodesOffCadButRightVolume) {
  const occ::Solid box = occ::make_box(4, 2, 2);
  HexMesh m = structured_grid(2, 2, 2);
  m.append(structured_grid(2, 2, 2, 1.0, Vec3(2, 0, 0)));
  classify_by_geometry(m, box);
  const CheckReport r = check_mesh(m, &box);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.boundary_quads, 48u);
  ASSERT_NE(find(r, "nodes_off_cad"), nullptr);
  EXPECT_NEAR(r.max_boundary_distance, 1.0, 1e-9);  // the nodes at (2, 1, 1)
  EXPECT_NEAR(r.mesh_volume, 16.0, 1e-12);
  EXPECT_EQ(find(r, "volume_mismatch"), nullptr);
}

TEST(CheckMeshCad, TaperedBrickMeshMatchesExactly) {
  const double dx = 4, dy = 3, dz = 2, t = 0.5;
  const occ::Solid brick = occ::make_tapered_brick(dx, dy, dz, t);
  // 2x2x2 trilinear subdivision of the single hex: planar sides keep nodes on the CAD.
  const Vec3 c[8] = {
      Vec3(0, 0, 0),  Vec3(dx, 0, 0),      Vec3(dx, dy, 0),          Vec3(0, dy, 0),
      Vec3(t, t, dz), Vec3(dx - t, t, dz), Vec3(dx - t, dy - t, dz), Vec3(t, dy - t, dz)};
  HexMesh m = structured_grid(2, 2, 2, 0.5);
  for (std::size_t n = 0; n < m.num_nodes(); ++n) {
    const NodeId id(static_cast<std::int32_t>(n));
    const Vec3 r = m.point(id);
    const double u = r.x(), v = r.y(), w = r.z();
    m.set_point(id, (1 - u) * (1 - v) * (1 - w) * c[0] + u * (1 - v) * (1 - w) * c[1] +
                        u * v * (1 - w) * c[2] + (1 - u) * v * (1 - w) * c[3] +
                        (1 - u) * (1 - v) * w * c[4] + u * (1 - v) * w * c[5] + u * v * w * c[6] +
                        (1 - u) * v * w * c[7]);
  }
  classify_by_geometry(m, brick);
  const CheckReport r = check_mesh(m, &brick);
  EXPECT_TRUE(r.valid) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics[0]));
  const double expected =
      dz / 6 * (dx * dy + (dx - 2 * t) * (dy - 2 * t) + 4 * (dx - t) * (dy - t));
  EXPECT_NEAR(r.mesh_volume, expected, 1e-12);
  EXPECT_NEAR(r.cad_volume, expected, 1e-9);
  EXPECT_GT(r.scaled_jacobian.min, 0.0);
  EXPECT_LT(r.scaled_jacobian.min, 1.0);
}

// A mesh whose nodes all lie on the CAD can still cut a corner off: two nodes of a box's
// top front edge moved onto the top face leave the front quad between them spanning the
// front and the top faces with no node on the edge. The check names the edge, and the quad
// is no chord of the surface: the chord allowance took its centre's distance as chord error
// and excused the missing volume (HexMe i22's multisweeps cut a boss's rim off so, 0.8 % of
// the volume, and passed unnoticed); now the volume is checked without it.
TEST(CheckMeshCad, AQuadAcrossASharpEdgeIsNamed) {
  const occ::Solid box = occ::make_box(3, 1, 1);
  HexMesh m = structured_grid(3, 1, 1);
  for (int i : {1, 2}) {
    const NodeId n(static_cast<std::int32_t>(grid_node(3, 1, i, 0, 1)));
    m.set_point(n, Vec3(i, 0.3, 1));
  }
  classify_by_geometry(m, box);
  const CheckReport r = check_mesh(m, &box);
  EXPECT_LT(r.max_boundary_distance, 1e-9);
  const auto* across = find(r, "boundary_across_edges");
  ASSERT_NE(across, nullptr);
  EXPECT_FALSE(r.valid);
  EXPECT_NE(find(r, "volume_mismatch"), nullptr);
  EXPECT_LT(r.volume_allowance, std::abs(r.mesh_volume - r.cad_volume));
  EXPECT_EQ(across->severity, core::Severity::warning);
  EXPECT_EQ(across->message.rfind("1 boundary quads", 0), 0u) << across->message;
  ASSERT_EQ(across->entities.size(), 1u);
  // The edge named is the top front one (y = 0, z = 1).
  core::EdgeId named;
  for (core::EdgeId e : box.edges())
    if (core::entity_name(e) == across->entities[0]) named = e;
  ASSERT_TRUE(named.valid());
  const Vec3 mid = box.edge_points_by_length(named, 2)[1];
  EXPECT_NEAR(mid.y(), 0, 1e-9);
  EXPECT_NEAR(mid.z(), 1, 1e-9);
  // Read back from a .msh file, whose named groups carry the classification, it is seen too.
  io::WriteOptions w;
  w.groups = io::named_groups(m, box);
  const std::string path = ::testing::TempDir() + "/across_edge.msh";
  std::string error;
  ASSERT_TRUE(io::write_mesh(m, path, w, &error)) << error;
  const io::ReadMeshResult back = io::read_mesh(path);
  ASSERT_TRUE(back.ok);
  const CheckReport from_file = check_mesh(back.mesh, &box);
  const auto* again = find(from_file, "boundary_across_edges");
  ASSERT_NE(again, nullptr);
  EXPECT_EQ(again->entities, across->entities);
  // The same grid untouched has none.
  HexMesh plain = structured_grid(3, 1, 1);
  classify_by_geometry(plain, box);
  EXPECT_EQ(find(check_mesh(plain, &box), "boundary_across_edges"), nullptr);
}

// A quad across an edge that is not sharp (20 degrees) but not tangent either cuts the
// corner off as well: no chord, no allowance for it. One hex fills a prism whose top is a
// ridge of two planes; its top quad spans both, 8 % of the volume under it. Counted as a
// chord (its centre 0.17 below the ridge, times its area 2) it excused 0.34 and passed.
TEST(CheckMeshCad, AQuadAcrossAShallowRidgeIsNoChord) {
  const double t = std::tan(10 * M_PI / 180);  // each half of the top turns 10 degrees
  const occ::Solid ridge = occ::make_prism({{0, 0}, {2, 0}, {2, 1}, {1, 1 + t}, {0, 1}}, 1);
  HexMesh m = structured_grid(1, 1, 1);
  for (std::size_t n = 0; n < m.num_nodes(); ++n) {
    const NodeId id(static_cast<std::int32_t>(n));
    const Vec3 p = m.points()[n];
    m.set_point(id, Vec3(2 * p.x(), p.y(), p.z()));
  }
  classify_by_geometry(m, ridge);
  const CheckReport r = check_mesh(m, &ridge);
  EXPECT_LT(r.max_boundary_distance, 1e-9);
  EXPECT_NEAR(r.cad_volume - r.mesh_volume, t, 1e-9);
  EXPECT_NE(find(r, "volume_mismatch"), nullptr);
  EXPECT_FALSE(r.valid);
  // Not sharp: not named as a corner cut off at a sharp edge.
  EXPECT_EQ(find(r, "boundary_across_edges"), nullptr);
}

TEST(CheckMeshCad, CurvedFaceGetsChordAllowance) {
  // Cylinder r = 1, h = 1 meshed by a 5-block o-grid: an inner square of half-side a and
  // four hexes out to nodes on the circles at 45 degrees. Lateral quads are chords.
  const occ::Solid cyl = occ::make_cylinder(1.0, 1.0);
  const double a = 0.35, s = std::sqrt(0.5);
  HexMesh m;
  const double inner[4][2] = {{-a, -a}, {a, -a}, {a, a}, {-a, a}};
  const double outer[4][2] = {{-s, -s}, {s, -s}, {s, s}, {-s, s}};
  for (double z : {0.0, 1.0}) {
    for (const auto& p : inner) m.add_node(Vec3(p[0], p[1], z));
    for (const auto& p : outer) m.add_node(Vec3(p[0], p[1], z));
  }
  auto hex = [&](std::array<int, 4> q) {  // a counter-clockwise quad at z = 0, extruded
    m.add_hex({q[0], q[1], q[2], q[3], q[0] + 8, q[1] + 8, q[2] + 8, q[3] + 8});
  };
  hex({0, 1, 2, 3});
  for (int i = 0; i < 4; ++i) hex({i, 4 + i, 4 + (i + 1) % 4, (i + 1) % 4});
  classify_by_geometry(m, cyl);
  for (int n : {4, 5, 6, 7}) EXPECT_EQ(m.node_class(NodeId(n)).dim, 1);
  const CheckReport r = check_mesh(m, &cyl);
  EXPECT_TRUE(r.valid) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics[0]));
  EXPECT_EQ(r.non_positive, 0u);
  EXPECT_NEAR(r.mesh_volume, 2.0, 1e-12);  // the square inscribed in the unit circle
  EXPECT_NEAR(r.cad_volume, M_PI, 1e-6);
  // Four lateral quads of area sqrt(2), centres 1 - sqrt(1/2) inside the cylinder.
  const double chord = 4 * std::sqrt(2.0) * (1 - s);
  EXPECT_NEAR(r.volume_allowance, chord + 1e-9 * r.cad_volume, 1e-6);
  EXPECT_LT(r.max_boundary_distance, 1e-7);
}

}  // namespace
}  // namespace vorohex::quality
