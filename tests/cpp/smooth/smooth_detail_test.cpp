// The smoothing kernels: adjacency arrays and the local objective's gradient.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mesh/map_block.h"
#include "occ/primitives.h"
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
