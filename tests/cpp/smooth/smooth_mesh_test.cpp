// smooth_mesh on mapped meshes of CAD solids: untangling, the never-lower minimum, nodes kept
// on their CAD entities, options and cancellation.
#include "smooth/smooth_mesh.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <random>
#include <stdexcept>

#include "mesh/map_block.h"
#include "occ/primitives.h"
#include "quality/check_mesh.h"
#include "quality/scaled_jacobian.h"

namespace vorohex::smooth {
namespace {

using core::EdgeId;
using core::FaceId;
using core::HexMesh;
using core::NodeClass;
using core::NodeId;
using core::Vec3;
using core::VertexId;

HexMesh mapped(const occ::Solid& solid, double size) {
  mesh::MapBlockOptions o;
  o.size = size;
  mesh::MapBlockResult r = mesh::map_block(solid, o);
  EXPECT_TRUE(r.ok);
  return std::move(r.mesh);
}

std::size_t count_inverted(const HexMesh& m) {
  std::size_t n = 0;
  for (double v : quality::scaled_jacobians(m)) n += v <= 0;
  return n;
}

double min_sj(const HexMesh& m) {
  double lo = 1;
  for (double v : quality::scaled_jacobians(m)) lo = std::min(lo, v);
  return lo;
}

// Random displacement of every non-vertex node by up to `amplitude` (model units) along its
// entity: free for interior nodes, in the tangent plane of planar face nodes, along the
// chord of straight edge nodes. Valid for solids with planar faces and straight edges.
void perturb_planar(HexMesh& m, const occ::Solid& s, double amplitude, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  for (std::size_t i = 0; i < m.num_nodes(); ++i) {
    const NodeId id(static_cast<std::int32_t>(i));
    const NodeClass c = m.node_class(id);
    const Vec3 x = m.point(id);
    Vec3 d(u(rng), u(rng), u(rng));
    if (c.dim == 0) continue;
    if (c.dim == 2) {
      const Vec3 n = s.face_normal(FaceId(c.id), x);
      d -= d.dot(n) * n;
    } else if (c.dim == 1) {
      const Vec3 a = s.vertex_point(s.edge_first_vertex(EdgeId(c.id)));
      const Vec3 b = s.vertex_point(s.edge_last_vertex(EdgeId(c.id)));
      const Vec3 t = (b - a).normalized();
      d = d.dot(t) * t;
    }
    Vec3 y = x + d;
    if (c.dim == 2) y = s.project_to_face(FaceId(c.id), y);
    if (c.dim == 1) y = s.project_to_edge(EdgeId(c.id), y);
    m.set_point(id, y);
  }
}

// Every classified node lies on its entity within tol (absolute); vertices exactly.
void expect_on_cad(const HexMesh& m, const occ::Solid& s, double tol) {
  for (std::size_t i = 0; i < m.num_nodes(); ++i) {
    const NodeId id(static_cast<std::int32_t>(i));
    const NodeClass c = m.node_class(id);
    const Vec3& p = m.point(id);
    if (c.dim == 0) {
      EXPECT_EQ(p, s.vertex_point(VertexId(c.id))) << "node " << i;
    } else if (c.dim == 1) {
      EXPECT_LT(s.distance_to_edge(EdgeId(c.id), p), tol) << "node " << i;
    } else if (c.dim == 2) {
      EXPECT_LT(s.distance_to_face(FaceId(c.id), p), tol) << "node " << i;
    }
  }
}

void expect_valid(const HexMesh& m, const occ::Solid& s) {
  quality::CheckOptions o;
  o.distance_rel_tol = 1e-7;
  const quality::CheckReport r = quality::check_mesh(m, &s, o);
  EXPECT_TRUE(r.valid) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics[0]));
  EXPECT_EQ(r.non_positive, 0u);
  EXPECT_LE(r.max_boundary_distance_rel, 1e-7);
}

TEST(SmoothMesh, PerturbedBoxWithInvertedHexesIsUntangled) {
  const occ::Solid box = occ::make_box(4, 3, 2);
  const double h = 0.25;
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u}) {
    HexMesh m = mapped(box, h);
    std::mt19937 rng(seed);
    perturb_planar(m, box, 0.5 * h, rng);
    const std::size_t inverted = count_inverted(m);
    ASSERT_GT(inverted, 10u) << "the perturbation must invert some hexes";
    SmoothOptions o;
    const SmoothResult r = smooth_mesh(m, box, o);
    EXPECT_EQ(r.status, SmoothStatus::ok) << status_name(r.status);
    EXPECT_TRUE(r.ok());
    EXPECT_EQ(r.inverted_before, inverted);
    EXPECT_EQ(r.inverted_after, 0u);
    EXPECT_EQ(r.untangled, inverted);
    EXPECT_LE(r.min_before, 0);
    EXPECT_GT(r.min_after, 0.2) << "seed " << seed;
    EXPECT_GT(r.mean_after, r.mean_before);
    EXPECT_NEAR(r.min_after, min_sj(m), 1e-15);
    EXPECT_GT(r.laplacian_moves, 0u);
    EXPECT_GE(r.seconds, r.seconds_laplacian);
    expect_valid(m, box);
    expect_on_cad(m, box, 1e-7 * box.diagonal());
  }
}

// Fixed nodes (those on a face another mesh shares) stay exactly where they are while the
// rest untangles around them; untangle_folded says whether the result is free of inverted
// hexes and reaches its quality floor.
TEST(SmoothMesh, FixedNodesStayWhereTheyAre) {
  const occ::Solid box = occ::make_box(4, 3, 2);
  const double h = 0.25;
  HexMesh m = mapped(box, h);
  const std::vector<Vec3> grid = m.points();
  std::mt19937 rng(3);
  perturb_planar(m, box, 0.5 * h, rng);
  // Every node on the face z = 0 is fixed, where the mapped mesh put it (as a neighbour
  // meshed it).
  std::vector<char> fixed(m.num_nodes(), 0);
  std::size_t on_floor = 0;
  for (std::size_t i = 0; i < m.num_nodes(); ++i)
    if (std::abs(grid[i].z()) < 1e-12 && m.node_classes()[i].dim == 2) {
      fixed[i] = 1, ++on_floor;
      m.set_point(NodeId(std::int32_t(i)), grid[i]);
    }
  ASSERT_GT(on_floor, 50u);
  ASSERT_GT(count_inverted(m), 10u);
  const std::vector<Vec3> before = m.points();
  HexMesh copy = m;
  EXPECT_TRUE(untangle_folded(copy, box, fixed, nullptr, {}, 0.05));
  std::size_t moved = 0;
  for (std::size_t i = 0; i < m.num_nodes(); ++i) {
    if (fixed[i]) EXPECT_EQ(copy.points()[i], before[i]) << "node " << i;
    moved += copy.points()[i] != before[i];
  }
  EXPECT_GT(moved, 100u);
  EXPECT_EQ(count_inverted(copy), 0u);
  // A floor the result does not reach: untangled, but refused.
  HexMesh again = m;
  EXPECT_FALSE(untangle_folded(again, box, fixed, nullptr, {}, 0.99));
}

// Badly tangled input that a few untangling passes cannot fully clear: the inverted count
// falls, yet no hex ends below the input's minimum (before the per-move floor, these seeds
// ended with a lower minimum: seed 10 at 1.5 h went from -0.982 to -0.987).
TEST(SmoothMesh, TangledInputNeverEndsWithALowerMinimum) {
  const occ::Solid box = occ::make_box(2, 2, 1);
  const double h = 0.2;
  for (double amplitude : {1.5, 3.0})
    for (unsigned seed = 0; seed < 15; ++seed) {
      HexMesh m = mapped(box, h);
      std::mt19937 rng(seed);
      std::uniform_real_distribution<double> u(-amplitude * h, amplitude * h);
      for (std::size_t i = 0; i < m.num_nodes(); ++i) {
        const NodeId id(static_cast<std::int32_t>(i));
        if (m.node_class(id).dim == 3) m.set_point(id, m.point(id) + Vec3(u(rng), u(rng), u(rng)));
      }
      const double before = min_sj(m);
      ASSERT_LT(before, 0);
      SmoothOptions o;
      o.laplacian_iterations = 0;
      o.optimisation_passes = 1 + 2 * (seed % 2);
      const SmoothResult r = smooth_mesh(m, box, o);
      EXPECT_EQ(r.min_before, before);
      EXPECT_GE(r.min_after, before) << "amplitude " << amplitude << " seed " << seed;
      EXPECT_NEAR(r.min_after, min_sj(m), 1e-15);
      EXPECT_LT(r.inverted_after, r.inverted_before) << "seed " << seed;
      for (const auto& d : r.diagnostics) EXPECT_NE(d.code, "smoothing_reverted");
    }
}

TEST(SmoothMesh, PositivePerturbationsNeverLowerTheMinimum) {
  const occ::Solid box = occ::make_box(2, 2, 1);
  for (unsigned seed = 10; seed < 16; ++seed) {
    const double h = 0.2;
    HexMesh m = mapped(box, h);
    std::mt19937 rng(seed);
    // Small random displacements that keep every hex positive.
    perturb_planar(m, box, (0.1 + 0.05 * (seed % 4)) * h, rng);
    ASSERT_EQ(count_inverted(m), 0u);
    const double before = min_sj(m);
    SmoothOptions o;
    o.laplacian_iterations = 3 + seed % 5;
    o.optimisation_passes = seed % 3;
    o.quality_target = 0.3 + 0.1 * (seed % 6);
    const SmoothResult r = smooth_mesh(m, box, o);
    EXPECT_TRUE(r.ok());
    EXPECT_EQ(r.min_before, before);
    EXPECT_GE(r.min_after, before) << "seed " << seed;
    EXPECT_EQ(count_inverted(m), 0u);
    expect_valid(m, box);
    expect_on_cad(m, box, 1e-7 * box.diagonal());
  }
}

TEST(SmoothMesh, RaisesTheMinimumOfAPerturbedBox) {
  const occ::Solid box = occ::make_box(2, 1, 1);
  HexMesh m = mapped(box, 0.125);
  std::mt19937 rng(42);
  perturb_planar(m, box, 0.15 * 0.125, rng);
  ASSERT_EQ(count_inverted(m), 0u);
  const SmoothResult r = smooth_mesh(m, box, SmoothOptions{});
  EXPECT_TRUE(r.ok());
  // A grid of cubes is the optimum; the smoother must get most of the way back.
  EXPECT_GT(r.min_after, r.min_before + 0.2);
  EXPECT_GT(r.min_after, 0.8);
  EXPECT_GT(r.mean_after, 0.95);
}

TEST(SmoothMesh, TaperedBrickKeepsNodesOnTheirFacesAndNeverLowersTheMinimum) {
  const occ::Solid brick = occ::make_tapered_brick(4, 3, 2, 1.2);
  HexMesh m = mapped(brick, 0.25);
  const HexMesh input = m;
  const SmoothResult r = smooth_mesh(m, brick, SmoothOptions{});
  EXPECT_TRUE(r.ok());
  EXPECT_GE(r.min_after, r.min_before);
  EXPECT_GE(r.min_after, min_sj(input));
  EXPECT_EQ(r.inverted_after, 0u);
  EXPECT_EQ(r.fixed_nodes, 8u);
  for (std::size_t i = 0; i < m.num_nodes(); ++i) {
    const NodeId id(static_cast<std::int32_t>(i));
    if (m.node_class(id).dim == 0) {
      EXPECT_EQ(m.point(id), input.point(id));
    }
  }
  expect_on_cad(m, brick, 1e-7 * brick.diagonal());
  expect_valid(m, brick);

  // The same after a perturbation: nodes slide back along the slanted faces.
  HexMesh p = input;
  std::mt19937 rng(5);
  perturb_planar(p, brick, 0.03, rng);
  ASSERT_EQ(count_inverted(p), 0u);
  const double before = min_sj(p);
  const SmoothResult rp = smooth_mesh(p, brick, SmoothOptions{});
  EXPECT_TRUE(rp.ok());
  EXPECT_GE(rp.min_after, before);
  EXPECT_GT(rp.min_after, before);  // the perturbation left room to improve
  expect_on_cad(p, brick, 1e-7 * brick.diagonal());
  expect_valid(p, brick);
}

TEST(SmoothMesh, CurvedRingSectorNodesStayOnCylinders) {
  const occ::Solid ring = occ::make_ring_sector(1.0, 2.0, 1.2, 1.0);
  HexMesh m = mapped(ring, 0.15);
  // Move interior nodes only (face nodes sit on curved faces): a positive perturbation.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  for (std::size_t i = 0; i < m.num_nodes(); ++i) {
    const NodeId id(static_cast<std::int32_t>(i));
    if (m.node_class(id).is_interior()) m.set_point(id, m.point(id) + Vec3(u(rng), u(rng), u(rng)));
  }
  ASSERT_EQ(count_inverted(m), 0u);
  const double before = min_sj(m);
  SmoothOptions o;
  o.laplacian_iterations = 10;
  const SmoothResult r = smooth_mesh(m, ring, o);
  EXPECT_TRUE(r.ok());
  EXPECT_GE(r.min_after, before);
  EXPECT_GT(r.min_after, 0.2);
  expect_on_cad(m, ring, 1e-7 * ring.diagonal());
  expect_valid(m, ring);
}

TEST(SmoothMesh, NodesOnUnknownEntitiesStayFixed) {
  const occ::Solid box = occ::make_box(1, 1, 1);
  HexMesh m = mapped(box, 0.25);
  std::mt19937 rng(9);
  perturb_planar(m, box, 0.05, rng);
  // Claim a face node lies on Face 99: it must neither move nor be projected.
  NodeId victim(-1);
  for (std::size_t i = 0; i < m.num_nodes() && !victim.valid(); ++i)
    if (m.node_classes()[i].dim == 2) victim = NodeId(static_cast<std::int32_t>(i));
  ASSERT_TRUE(victim.valid());
  m.set_node_class(victim, NodeClass::on(FaceId(99)));
  const Vec3 where = m.point(victim);
  const SmoothResult r = smooth_mesh(m, box, SmoothOptions{});
  EXPECT_EQ(m.point(victim), where);
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_EQ(r.diagnostics[0].code, "unknown_entity");
  EXPECT_EQ(r.diagnostics[0].severity, core::Severity::warning);
  EXPECT_EQ(r.fixed_nodes, 9u);
  EXPECT_TRUE(r.ok());
}

TEST(SmoothMesh, CancelledBeforeTheFirstSweepLeavesTheMeshAlone) {
  const occ::Solid box = occ::make_box(1, 1, 1);
  HexMesh m = mapped(box, 0.2);
  std::mt19937 rng(4);
  perturb_planar(m, box, 0.04, rng);
  const HexMesh input = m;
  std::atomic<bool> cancel{true};
  const SmoothResult r = smooth_mesh(m, box, SmoothOptions{}, core::Progress({}, &cancel));
  EXPECT_EQ(r.status, SmoothStatus::cancelled);
  EXPECT_STREQ(status_name(r.status), "cancelled");
  EXPECT_EQ(r.laplacian_moves + r.optimisation_moves, 0u);
  EXPECT_EQ(m.points(), input.points());
}

TEST(SmoothMesh, ReportsProgressAndHandlesAnEmptyMesh) {
  const occ::Solid box = occ::make_box(1, 1, 1);
  HexMesh empty;
  int calls = 0;
  double last = -1;
  const core::Progress progress([&](std::string_view stage, double f) {
    EXPECT_EQ(stage, "smooth");
    ++calls;
    last = f;
  });
  const SmoothResult r = smooth_mesh(empty, box, SmoothOptions{}, progress);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(last, 1.0);
  HexMesh m = mapped(box, 0.25);
  calls = 0;
  smooth_mesh(m, box, SmoothOptions{}, progress);
  EXPECT_GE(calls, 2);
  EXPECT_EQ(last, 1.0);
}

// The untangling runs again in rounds after the optimisation: the fractions reported never
// go back (they went 50 %, 75 %, 50 %, 75 % on HexMe n10's grid mesh), and end at 1. A
// labelled progress names the stage after the run it belongs to (the pipeline's retries).
TEST(SmoothMesh, ProgressNeverGoesBackAndCarriesItsLabel) {
  // One hexahedron turned inside out, its corners on the box's vertices: nothing can move,
  // so it stays inverted and the untangling's rounds run.
  const occ::Solid box = occ::make_box(4, 3, 2);
  const HexMesh one = mapped(box, 4);
  ASSERT_EQ(one.num_hexes(), 1u);
  HexMesh m;
  for (std::size_t n = 0; n < one.num_nodes(); ++n)
    m.add_node(one.points()[n], one.node_classes()[n]);
  const core::HexNodes& h = one.hexes()[0];
  m.add_hex({h[4], h[5], h[6], h[7], h[0], h[1], h[2], h[3]});
  ASSERT_EQ(count_inverted(m), 1u);
  std::vector<std::pair<std::string, double>> heard;
  const core::Progress progress(
      [&](std::string_view stage, double f) { heard.emplace_back(std::string(stage), f); });
  smooth_mesh(m, box, SmoothOptions{}, progress.labelled("finer grid"));
  ASSERT_GE(heard.size(), 3u);
  for (std::size_t k = 0; k < heard.size(); ++k) {
    EXPECT_EQ(heard[k].first, "finer grid: smooth");
    if (k > 0) EXPECT_GE(heard[k].second, heard[k - 1].second) << "report " << k;
  }
  EXPECT_EQ(heard.back().second, 1.0);
}

TEST(SmoothOptions, ValidateNamesTheBadField) {
  auto message = [](SmoothOptions o) -> std::string {
    try {
      o.validate();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(message(SmoothOptions{}), "");
  SmoothOptions o;
  o.laplacian_iterations = -1;
  EXPECT_NE(message(o).find("laplacian_iterations"), std::string::npos);
  o = {};
  o.optimisation_passes = -2;
  EXPECT_NE(message(o).find("optimisation_passes"), std::string::npos);
  o = {};
  o.quality_target = 0;
  EXPECT_NE(message(o).find("quality_target"), std::string::npos);
  o.quality_target = 1.5;
  EXPECT_NE(message(o).find("quality_target"), std::string::npos);
  o = {};
  o.relaxation = 0;
  EXPECT_NE(message(o).find("relaxation"), std::string::npos);
  o = {};
  o.tolerance = std::nan("");
  EXPECT_NE(message(o).find("tolerance"), std::string::npos);
  HexMesh m;
  const occ::Solid box = occ::make_box(1, 1, 1);
  o = {};
  o.relaxation = 2;
  EXPECT_THROW(smooth_mesh(m, box, o), std::invalid_argument);
}

}  // namespace
}  // namespace vorohex::smooth
