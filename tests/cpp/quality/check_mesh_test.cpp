// check_mesh without CAD: the mesh-intrinsic invariants.
#include "quality/check_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "fixtures/diagnostics.h"
#include "quality/grid_fixture.h"

namespace vorohex::quality {
namespace {

using core::HexMesh;
using core::Vec3;
using testing::structured_grid;

const core::Diagnostic* find(const CheckReport& r, const std::string& code) {
  return vorohex::testing::find_diagnostic(r.diagnostics, code);
}

// Interior and boundary quad counts of an nx x ny x nz structured grid.
std::size_t grid_interior_quads(std::size_t nx, std::size_t ny, std::size_t nz) {
  return (nx - 1) * ny * nz + nx * (ny - 1) * nz + nx * ny * (nz - 1);
}
std::size_t grid_boundary_quads(std::size_t nx, std::size_t ny, std::size_t nz) {
  return 2 * (nx * ny + ny * nz + nx * nz);
}

// A copy of m without hex `removed`.
HexMesh without_hex(const HexMesh& m, std::size_t removed) {
  HexMesh out;
  for (const Vec3& p : m.points()) out.add_node(p);
  for (std::size_t h = 0; h < m.num_hexes(); ++h)
    if (h != removed) out.add_hex(m.hexes()[h]);
  return out;
}

TEST(CheckMesh, HexesOnTheSameSideOfASharedQuadAreOverlapping) {
  // A unit cube and a positive hex below its top face: both have positive scaled
  // Jacobians and share one quad, but lie on the same side of it.
  HexMesh m;
  for (int i = 0; i < 8; ++i)
    m.add_node(Vec3((i == 1 || i == 2 || i == 5 || i == 6), (i % 4 >= 2), i / 4));
  for (int i = 0; i < 4; ++i) m.add_node(Vec3(m.points()[i].x(), m.points()[i].y(), 0.5));
  m.add_hex({0, 1, 2, 3, 4, 5, 6, 7});
  m.add_hex({8, 9, 10, 11, 4, 5, 6, 7});
  const CheckReport r = check_mesh(m, nullptr);
  EXPECT_EQ(r.scaled_jacobian.inverted, 0u);
  EXPECT_EQ(r.interior_quads, 1u);
  EXPECT_EQ(r.folded_quads, 1u);
  EXPECT_FALSE(r.valid);
  ASSERT_NE(find(r, "overlapping_elements"), nullptr);
  // The same two hexes stacked properly are fine.
  HexMesh ok;
  for (int i = 0; i < 8; ++i) ok.add_node(m.points()[i]);
  for (int i = 0; i < 4; ++i) ok.add_node(m.points()[i + 4] + Vec3(0, 0, 1));
  ok.add_hex({0, 1, 2, 3, 4, 5, 6, 7});
  ok.add_hex({4, 5, 6, 7, 8, 9, 10, 11});
  const CheckReport r_ok = check_mesh(ok, nullptr);
  EXPECT_EQ(r_ok.folded_quads, 0u);
  EXPECT_TRUE(r_ok.valid);
}

TEST(CheckMesh, StructuredGridIsValidWithExactQuadCounts) {
  const HexMesh m = structured_grid(3, 2, 1);
  const CheckReport r = check_mesh(m, nullptr);
  EXPECT_TRUE(r.valid);
  EXPECT_TRUE(r.diagnostics.empty());
  EXPECT_EQ(r.nodes, 24u);
  EXPECT_EQ(r.hexes, 6u);
  EXPECT_EQ(r.interior_quads, grid_interior_quads(3, 2, 1));  // 2*2*1 + 3*1*1 + 0 = 7
  EXPECT_EQ(r.boundary_quads, grid_boundary_quads(3, 2, 1));  // 2 (6 + 2 + 3) = 22
  EXPECT_EQ(r.interior_quads, 7u);
  EXPECT_EQ(r.boundary_quads, 22u);
  EXPECT_EQ(2 * r.interior_quads + r.boundary_quads, 6 * r.hexes);
  EXPECT_EQ(r.non_manifold_quads, 0u);
  EXPECT_EQ(r.open_boundary_edges, 0u);
  EXPECT_EQ(r.unused_nodes, 0u);
  EXPECT_EQ(r.non_positive, 0u);
  EXPECT_EQ(r.scaled_jacobian.count, 6u);
  EXPECT_DOUBLE_EQ(r.scaled_jacobian.min, 1.0);
  EXPECT_EQ(r.scaled_jacobian.histogram[19], 6u);
  EXPECT_NEAR(r.mesh_volume, 6.0, 1e-12);
  EXPECT_FALSE(r.has_cad);
}

TEST(CheckMesh, InvertedHexIsReportedByIndex) {
  HexMesh m = structured_grid(3, 2, 1);
  // Hex 4 with its two quads swapped: same faces (conformity intact), inside out.
  HexMesh flipped;
  for (const Vec3& p : m.points()) flipped.add_node(p);
  for (std::size_t h = 0; h < m.num_hexes(); ++h) {
    core::HexNodes n = m.hexes()[h];
    if (h == 4) n = {n[4], n[5], n[6], n[7], n[0], n[1], n[2], n[3]};
    flipped.add_hex(n);
  }
  const CheckReport r = check_mesh(flipped, nullptr);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.non_positive, 1u);
  EXPECT_EQ(r.scaled_jacobian.inverted, 1u);
  EXPECT_DOUBLE_EQ(r.scaled_jacobian.min, -1.0);
  const auto* d = find(r, "inverted_elements");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->severity, core::Severity::error);
  EXPECT_NE(d->message.find("hexes 4"), std::string::npos) << d->message;
  EXPECT_EQ(r.interior_quads, 7u);
  EXPECT_EQ(r.open_boundary_edges, 0u);
  EXPECT_NEAR(r.mesh_volume, 4.0, 1e-12);  // 5 - 1
}

TEST(CheckMesh, ManyInvertedHexesListAtMostTen) {
  HexMesh m = structured_grid(4, 4, 1);
  for (std::size_t n = 0; n < m.num_nodes(); ++n) {
    const core::NodeId id(static_cast<std::int32_t>(n));
    m.set_point(id, Vec3(m.point(id).x(), m.point(id).y(), -m.point(id).z()));  // mirror
  }
  const CheckReport r = check_mesh(m, nullptr);
  EXPECT_EQ(r.non_positive, 16u);
  const auto* d = find(r, "inverted_elements");
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find("and 6 more"), std::string::npos) << d->message;
}

TEST(CheckMesh, DuplicatedHexIsNonManifold) {
  HexMesh m = structured_grid(3, 2, 1);
  m.add_hex(m.hexes()[0]);  // hex 0 has two neighbours (+x and +y)
  const CheckReport r = check_mesh(m, nullptr);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.non_manifold_quads, 2u);
  ASSERT_NE(find(r, "non_manifold_faces"), nullptr);
  // Its four outer quads now count twice (interior), leaving a hole in the boundary.
  EXPECT_EQ(r.boundary_quads, 22u - 4u);
  EXPECT_GT(r.open_boundary_edges, 0u);
  EXPECT_NE(find(r, "open_boundary"), nullptr);
}

// The topology alone (what smoothing cannot change) counts the same as the whole check,
// and sees nothing of element quality: an inverted hex is not its business.
TEST(CheckMesh, TopologyAloneCountsWhatTheCheckCounts) {
  HexMesh m = structured_grid(3, 2, 1);
  m.add_hex(m.hexes()[0]);
  const CheckReport whole = check_mesh(m, nullptr), topology = check_topology(m);
  EXPECT_EQ(topology.non_manifold_quads, whole.non_manifold_quads);
  EXPECT_EQ(topology.open_boundary_edges, whole.open_boundary_edges);
  EXPECT_EQ(topology.boundary_quads, whole.boundary_quads);
  EXPECT_NE(find(topology, "open_boundary"), nullptr);
  HexMesh inverted = structured_grid(2, 1, 1);
  inverted.set_point(core::NodeId(0), Vec3(1.5, 0.5, 0.5));
  const CheckReport sound = check_topology(inverted);
  EXPECT_EQ(sound.open_boundary_edges, 0u);
  EXPECT_EQ(sound.non_manifold_quads, 0u);
  EXPECT_TRUE(sound.diagnostics.empty());
}

TEST(CheckMesh, RepeatedNodeIsDegenerate) {
  HexMesh m = structured_grid(2, 1, 1);
  core::HexNodes n = m.hexes()[1];
  n[6] = n[5];  // collapse edge 5-6
  HexMesh d;
  for (const Vec3& p : m.points()) d.add_node(p);
  d.add_hex(m.hexes()[0]);
  d.add_hex(n);
  const CheckReport r = check_mesh(d, nullptr);
  EXPECT_FALSE(r.valid);
  ASSERT_NE(find(r, "degenerate_elements"), nullptr);
  EXPECT_NE(find(r, "degenerate_elements")->message.find("hexes 1"), std::string::npos);
  EXPECT_EQ(r.non_positive, 1u);  // collapsed edge: scaled Jacobian 0
}

TEST(CheckMesh, UnusedNodeIsOnlyAWarning) {
  HexMesh m = structured_grid(2, 2, 2);
  m.add_node(Vec3(10, 10, 10));
  const CheckReport r = check_mesh(m, nullptr);
  EXPECT_TRUE(r.valid);
  EXPECT_EQ(r.unused_nodes, 1u);
  const auto* d = find(r, "unused_nodes");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->severity, core::Severity::warning);
}

TEST(CheckMesh, NodeIndexOutOfRangeIsInvalidWithoutCrashing) {
  HexMesh m = structured_grid(1, 1, 1);
  core::HexNodes n = m.hexes()[0];
  n[3] = 99;
  m.add_hex(n);
  const CheckReport r = check_mesh(m, nullptr);
  EXPECT_FALSE(r.valid);
  ASSERT_NE(find(r, "invalid_node_index"), nullptr);
  EXPECT_EQ(r.hexes, 2u);
}

TEST(CheckMesh, BadClassificationWithoutCad) {
  HexMesh m = structured_grid(1, 1, 1);
  m.set_node_class(core::NodeId(2), core::NodeClass{2, 0});  // face id 0 does not exist
  m.set_node_class(core::NodeId(5), core::NodeClass{7, 1});  // no such dimension
  m.set_node_class(core::NodeId(1), core::NodeClass::on(core::FaceId(4)));  // fine
  const CheckReport r = check_mesh(m, nullptr);
  EXPECT_FALSE(r.valid);
  const auto* d = find(r, "bad_classification");
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find("nodes 2, 5"), std::string::npos) << d->message;
}

TEST(CheckMesh, RemovedInteriorHexLeavesClosedCavity) {
  const HexMesh m = without_hex(structured_grid(3, 3, 3), 13);  // the centre cell
  const CheckReport r = check_mesh(m, nullptr);
  EXPECT_TRUE(r.valid);
  EXPECT_EQ(r.boundary_quads, grid_boundary_quads(3, 3, 3) + 6);
  EXPECT_EQ(r.interior_quads, grid_interior_quads(3, 3, 3) - 6);
  EXPECT_EQ(r.open_boundary_edges, 0u);
  EXPECT_NEAR(r.mesh_volume, 26.0, 1e-12);
}

TEST(CheckMesh, RemovedBoundaryEdgeHexKeepsBoundaryClosed) {
  const HexMesh m = without_hex(structured_grid(3, 3, 3), 0);  // a corner cell: a notch
  const CheckReport r = check_mesh(m, nullptr);
  EXPECT_TRUE(r.valid);
  EXPECT_EQ(r.boundary_quads, grid_boundary_quads(3, 3, 3));  // 3 removed, 3 exposed
}

TEST(CheckMesh, TwoHexesSharingOnlyAnEdgeHaveNonManifoldBoundaryEdge) {
  HexMesh m = structured_grid(2, 2, 1);
  HexMesh diag = without_hex(without_hex(m, 3), 0);  // keep cells (1,0) and (0,1)
  const CheckReport r = check_mesh(diag, nullptr);
  EXPECT_EQ(r.interior_quads, 0u);
  EXPECT_EQ(r.boundary_quads, 12u);
  EXPECT_EQ(r.open_boundary_edges, 1u);  // the shared vertical edge lies in 4 quads
  EXPECT_FALSE(r.valid);
}

TEST(CheckMesh, UnmergedBlocksLookClosedWithoutCad) {
  // Two 2x2x2 blocks side by side with separate nodes on the plane x = 2: each block is
  // closed, so only the doubled boundary count (and the CAD checks) reveals the gap.
  HexMesh m = structured_grid(2, 2, 2);
  m.append(structured_grid(2, 2, 2, 1.0, Vec3(2, 0, 0)));
  const CheckReport r = check_mesh(m, nullptr);
  EXPECT_TRUE(r.valid);
  EXPECT_EQ(r.boundary_quads, 48u);  // a merged 4x2x2 grid has 40
  EXPECT_EQ(r.interior_quads, 24u);
  EXPECT_NEAR(r.mesh_volume, 16.0, 1e-12);
}

TEST(CheckMesh, EmptyMeshIsValidAndZero) {
  const CheckReport r = check_mesh(HexMesh{}, nullptr);
  EXPECT_TRUE(r.valid);
  EXPECT_EQ(r.hexes, 0u);
  EXPECT_EQ(r.scaled_jacobian.count, 0u);
  EXPECT_EQ(r.mesh_volume, 0.0);
}

TEST(CheckOptions, ValidateNamesTheBadField) {
  CheckOptions o;
  EXPECT_NO_THROW(o.validate());
  o.volume_rel_tol = std::numeric_limits<double>::quiet_NaN();
  try {
    o.validate();
    FAIL() << "NaN accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("volume_rel_tol"), std::string::npos);
  }
  o = CheckOptions{};
  o.distance_rel_tol = -1e-3;
  try {
    o.validate();
    FAIL() << "negative accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("distance_rel_tol"), std::string::npos);
  }
  EXPECT_THROW(check_mesh(structured_grid(1, 1, 1), nullptr, o), std::invalid_argument);
}

TEST(CheckMeshScale, MillionHexGridIsValid) {
  const HexMesh m = structured_grid(100, 100, 100, 0.01);
  const auto start = std::chrono::steady_clock::now();
  const CheckReport r = check_mesh(m, nullptr);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RecordProperty("check_mesh_seconds", std::to_string(seconds));
  std::printf("check_mesh on 1M hexes: %.3f s\n", seconds);
  EXPECT_TRUE(r.valid);
  EXPECT_EQ(r.interior_quads, grid_interior_quads(100, 100, 100));
  EXPECT_EQ(r.boundary_quads, grid_boundary_quads(100, 100, 100));
  EXPECT_NEAR(r.mesh_volume, 1.0, 1e-9);
  EXPECT_NEAR(r.scaled_jacobian.min, 1.0, 1e-12);
}

}  // namespace
}  // namespace vorohex::quality
