// The smoothing kernels: adjacency arrays and the local objective's gradient.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mesh/map_block.h"
#include "occ/primitives.h"
#include "quality/scaled_jacobian.h"
#include "smooth/detail/hex_jacobian.h"
#include "smooth/detail/node_objective.h"
#include "smooth/detail/topology.h"

namespace vorohex::smooth::detail {
namespace {

using core::Vec3;

std::array<Vec3, 8> unit_cube() {
  return {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
          Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
}

TEST(SmoothTopology, MappedBoxAdjacency) {
  const occ::Solid box = occ::make_box(3, 2, 1);
  mesh::MapBlockOptions o;
  o.size = 0.5;
  const mesh::MapBlockResult r = mesh::map_block(box, o);
  ASSERT_TRUE(r.ok);
  const auto& n = r.intervals;  // 6 x 4 x 2
  const SmoothTopology t = build_topology(r.mesh);
  EXPECT_EQ(t.boundary_quads, std::size_t(2 * (n[0] * n[1] + n[1] * n[2] + n[0] * n[2])));
  ASSERT_EQ(t.node_hexes.rows(), r.mesh.num_nodes());
  ASSERT_EQ(t.neighbours.rows(), r.mesh.num_nodes());
  EXPECT_EQ(t.node_hexes.items.size(), 8 * r.mesh.num_hexes());
  int counted[4] = {0, 0, 0, 0};
  for (std::size_t i = 0; i < r.mesh.num_nodes(); ++i) {
    const core::NodeClass c = r.mesh.node_classes()[i];
    const std::int64_t expected[4] = {0, 2, 4, 6};  // vertex, edge, face, interior
    EXPECT_EQ(t.neighbours.size(i), expected[c.dim]) << "node " << i << " dim " << int(c.dim);
    const std::int64_t hexes[4] = {1, 2, 4, 8};
    EXPECT_EQ(t.node_hexes.size(i), hexes[c.dim]) << i;
    ++counted[c.dim];
    // Every (hex, corner) item really names the node.
    for (std::int64_t k = t.node_hexes.begin(i); k < t.node_hexes.end(i); ++k) {
      const std::int32_t item = t.node_hexes.items[k];
      EXPECT_EQ(r.mesh.hexes()[item / 8][item % 8], static_cast<std::int32_t>(i));
    }
    // Edge nodes only see nodes of their own edge or model vertices.
    if (c.dim == 1)
      for (std::int64_t k = t.neighbours.begin(i); k < t.neighbours.end(i); ++k) {
        const core::NodeClass o = r.mesh.node_classes()[t.neighbours.items[k]];
        EXPECT_TRUE(o.dim == 0 || (o.dim == 1 && o.id == c.id));
      }
  }
  EXPECT_EQ(counted[0], 8);
  EXPECT_GT(counted[3], 0);
}

TEST(HexScaledJacobian, BitwiseEqualToTheQualityModule) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-0.6, 0.6);
  int inverted = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    std::array<Vec3, 8> p = unit_cube();
    const double scale = std::pow(10.0, trial % 7 - 3);
    for (auto& q : p) q = scale * (q + Vec3(jitter(rng), jitter(rng), jitter(rng)));
    const double expected = quality::scaled_jacobian(p);
    EXPECT_EQ(hex_scaled_jacobian(p), expected) << trial;  // exact, not near
    inverted += expected <= 0;
  }
  EXPECT_GT(inverted, 100);  // both signs were exercised
  // Collapsed edges, collapsed hexes and non-finite points are invalid (0), as in quality/.
  std::array<Vec3, 8> p = unit_cube();
  p[1] = p[0];
  EXPECT_EQ(hex_scaled_jacobian(p), 0.0);
  EXPECT_EQ(quality::scaled_jacobian(p), 0.0);
  std::array<Vec3, 8> flat;
  flat.fill(Vec3(1, 2, 3));
  EXPECT_EQ(hex_scaled_jacobian(flat), 0.0);
  p = unit_cube();
  p[5].x() = std::nan("");
  EXPECT_EQ(hex_scaled_jacobian(p), 0.0);
  EXPECT_EQ(hex_scaled_jacobian(unit_cube()), 1.0);
}

TEST(NodeObjective, CubeCornerIsOptimalAndScaleInvariant) {
  for (double scale : {1.0, 1e-3, 1e3}) {
    std::vector<IncidentHex> hexes(1);
    for (int i = 0; i < 8; ++i) hexes[0].points[i] = scale * unit_cube()[i];
    hexes[0].corner = 6;
    const ObjectiveValue v = node_objective(hexes, hexes[0].points[6], 0);
    EXPECT_NEAR(v.value, 4.0, 1e-12);  // four frames, each with inverse mean ratio 1
    EXPECT_LT(v.gradient.norm() * scale, 1e-12);
    EXPECT_NEAR(v.min_det, scale * scale * scale, 1e-12 * scale * scale * scale);
    EXPECT_NEAR(v.mean_edge, scale, 1e-12 * scale);
  }
}

TEST(NodeObjective, GradientMatchesFiniteDifferences) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<IncidentHex> hexes(2);
    for (int h = 0; h < 2; ++h) {
      for (int i = 0; i < 8; ++i)
        hexes[h].points[i] = unit_cube()[i] + Vec3(jitter(rng), jitter(rng), jitter(rng));
      hexes[h].corner = (trial + 3 * h) % 8;
    }
    // Some trials push the node through the opposite face: inverted corners need delta > 0.
    Vec3 x = hexes[0].points[hexes[0].corner];
    if (trial % 3 == 0) x = Vec3(0.5, 0.5, 0.5) + 1.5 * (Vec3(0.5, 0.5, 0.5) - x);
    hexes[1].points[hexes[1].corner] = x;
    const ObjectiveValue v0 = node_objective(hexes, x, 0);
    const double delta = choose_delta(v0.min_det, v0.mean_edge);
    if (v0.min_det <= 0) {
      EXPECT_GT(delta, 0);
    }
    const ObjectiveValue v = node_objective(hexes, x, delta);
    ASSERT_TRUE(std::isfinite(v.value)) << trial;
    EXPECT_NEAR(v.value, node_objective_value(hexes, x, delta), 1e-12 * v.value);
    const double h = 1e-6;
    for (int k = 0; k < 3; ++k) {
      Vec3 e = Vec3::Zero();
      e[k] = h;
      const double fd =
          (node_objective_value(hexes, x + e, delta) - node_objective_value(hexes, x - e, delta)) /
          (2 * h);
      EXPECT_NEAR(v.gradient[k], fd, 1e-5 * (1 + std::abs(fd))) << "trial " << trial << " k " << k;
    }
  }
}

TEST(NodeObjective, InvertedCornerWithoutRegularisationIsInfinite) {
  std::vector<IncidentHex> hexes(1);
  hexes[0].points = unit_cube();
  hexes[0].corner = 6;
  const Vec3 through(0.2, 0.2, 0.2);  // node 6 pulled past the opposite corner
  EXPECT_TRUE(std::isinf(node_objective_value(hexes, through, 0)));
  EXPECT_EQ(choose_delta(1.0, 1.0), 0);
  const ObjectiveValue v = node_objective(hexes, through, choose_delta(-0.5, 1.0));
  EXPECT_TRUE(std::isfinite(v.value));
  // Descending must move the node back towards (1, 1, 1).
  EXPECT_GT(-v.gradient.dot(Vec3(1, 1, 1)), 0);
}

}  // namespace
}  // namespace vorohex::smooth::detail

namespace vorohex::smooth::detail {
namespace {

TEST(UntangleModel, FramesAreAffineAndTheStepUntanglesAPulledThroughCorner) {
  std::vector<IncidentHex> hexes(1);
  hexes[0].points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                     Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
  hexes[0].corner = 6;
  const Vec3 x(0.3, 0.2, 0.25);  // node 6 pulled through: several frames negative
  const auto frames = affine_frames(hexes, x);
  ASSERT_EQ(frames.size(), 5u);  // four corner frames and the centre frame
  // Affine: the model predicts the determinants at another point exactly.
  const Vec3 y(0.9, 1.2, 0.8);
  const auto at_y = affine_frames(hexes, y);
  for (std::size_t i = 0; i < frames.size(); ++i)
    EXPECT_NEAR(frames[i].value + frames[i].gradient.dot(y - x), at_y[i].value, 1e-12) << i;
  const double u0 = untangle_value(frames, Vec3::Zero(), 0.2);
  EXPECT_GT(u0, 0);
  const Vec3 d = untangle_step(frames, 0.2, Eigen::Matrix3d::Identity(), 2.0);
  EXPECT_LT(untangle_value(frames, d, 0.2), 1e-3 * u0);
  std::array<Vec3, 8> p = hexes[0].points;
  p[6] = x + d;
  EXPECT_GT(hex_scaled_jacobian(p), 0);
  // Restricted to a line (an edge node), the step stays on it.
  Eigen::Matrix<double, 3, Eigen::Dynamic> line(3, 1);
  line << 0, 0, 1;
  const Vec3 dl = untangle_step(frames, 0.2, line, 2.0);
  EXPECT_EQ(dl.x(), 0);
  EXPECT_EQ(dl.y(), 0);
}

}  // namespace
}  // namespace vorohex::smooth::detail
