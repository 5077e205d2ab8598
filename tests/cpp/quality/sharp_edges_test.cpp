#include "quality/sharp_edges.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "fixtures/diagnostics.h"
#include "occ/primitives.h"
#include "occ/shape_io.h"
#include "pipeline/generate_mesh.h"

namespace vorohex::quality {
namespace {

// A prism on a triangle with a 10-degree corner (the other two 85 degrees), 5 deep.
occ::Solid wedge() {
  const double a = 10 * M_PI / 180;
  return occ::make_prism({{0, 0}, {10, 0}, {10 * std::cos(a), 10 * std::sin(a)}}, 5);
}

TEST(SharpEdges, AnEdgeAtTenDegreesBoundsEveryHexAlongItAtItsSine) {
  const occ::Solid s = wedge();
  const SharpEdges sharp = sharp_edges(s);
  // The edge along the 10-degree corner; the 85-degree ones (0.996) and the right angles
  // between the sides and the ends are no bound.
  ASSERT_EQ(sharp.edges.size(), 1u);
  EXPECT_NEAR(sharp.edges[0].angle, 10, 1e-6);
  EXPECT_NEAR(sharp.edges[0].bound, std::sin(10 * M_PI / 180), 1e-9);
  EXPECT_NEAR(sharp.bound(), std::sin(10 * M_PI / 180), 1e-6);
  // A box has nothing sharp; a concave edge (an L's inner corner) bounds nothing either.
  EXPECT_TRUE(sharp_edges(occ::make_box(2, 1, 1)).edges.empty());
  EXPECT_EQ(sharp_edges(occ::make_box(2, 1, 1)).bound(), 1);
  const occ::Solid l = occ::make_prism({{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}}, 1);
  EXPECT_TRUE(sharp_edges(l).edges.empty());
  // Asked for every bound below 1.01: still none (right angles bound nothing; the inner
  // corner's edge is concave).
  EXPECT_TRUE(sharp_edges(l, 1.01).edges.empty());
  // A prism on a triangle with 30, 60 and 90 degree corners: two edges, sin 30 and sin 60.
  const SharpEdges t =
      sharp_edges(occ::make_prism({{0, 0}, {2, 0}, {0, 2 * std::sqrt(3.0)}}, 1), 0.9);
  ASSERT_EQ(t.edges.size(), 2u);
  EXPECT_NEAR(t.edges[0].angle, 30, 1e-6);
  EXPECT_NEAR(t.edges[1].angle, 60, 1e-6);
  EXPECT_NEAR(t.bound(), 0.5, 1e-9);
}

// The bound is what a real mesh meets: the wedge meshed by the pipeline has its minimum at
// sin(10 degrees) or below, and a warning says why before meshing.
TEST(SharpEdges, ThePipelineSaysWhatTheGeometryAllows) {
  const occ::Solid s = wedge();
  const pipeline::MeshResult r = pipeline::generate_mesh(s, pipeline::MeshOptions{});
  ASSERT_TRUE(r.ok);
  EXPECT_LE(r.check.scaled_jacobian.min, std::sin(10 * M_PI / 180) + 1e-9);
  const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "geometry_bounds_quality");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->severity, core::Severity::warning);
  EXPECT_NE(d->message.find("at most 0.174"), std::string::npos) << d->message;
  EXPECT_NE(d->message.find("meet at 10 degrees inside the part"), std::string::npos) << d->message;
  ASSERT_FALSE(d->entities.empty());
  EXPECT_EQ(d->entities[0].rfind("Edge", 0), 0u) << d->entities[0];
  // The check's worst hexahedron lies on that edge: the user sees why it is the worst.
  ASSERT_FALSE(r.check.worst.empty());
  EXPECT_EQ(r.check.worst[0].scaled_jacobian, r.check.scaled_jacobian.min);
  const std::vector<std::string>& on = r.check.worst[0].entities;
  EXPECT_NE(std::find(on.begin(), on.end(), d->entities[0]), on.end()) << d->entities[0];
  // A box: no such info.
  const pipeline::MeshResult box =
      pipeline::generate_mesh(occ::make_box(2, 1, 1), pipeline::MeshOptions{});
  EXPECT_EQ(testing::find_diagnostic(box.diagnostics, "geometry_bounds_quality"), nullptr);
}

}  // namespace
}  // namespace vorohex::quality
