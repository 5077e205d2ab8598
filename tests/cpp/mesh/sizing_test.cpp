// What the meshers ask of local sizes (mesh/detail/sizing.h): counts and node spacing along
// an edge follow the field; without local sizes they are exactly the uniform ones.
#include "mesh/detail/sizing.h"

#include <gtest/gtest.h>

#include <cmath>

#include "occ/primitives.h"

namespace vorohex::mesh::detail {
namespace {

using core::Vec3;

// An edge of a 40 x 20 x 10 box starting at Vertex1, with a size of 0.5 at that vertex.
struct Fixture {
  occ::Solid box = occ::make_box(40, 20, 10);
  core::EdgeId edge;
  Fixture() {
    for (core::EdgeId e : box.edges())
      if (box.edge_first_vertex(e) == core::VertexId(1) && box.edge_length(e) > 39) edge = e;
  }
};

TEST(Sizing, WithoutLocalSizesCountsAndPointsAreUniform) {
  Fixture f;
  ASSERT_TRUE(f.edge.valid());
  const core::SizeField uniform(2.0);
  EXPECT_DOUBLE_EQ(edge_segments(f.box, f.edge, 2.0, nullptr), 20.0);
  EXPECT_DOUBLE_EQ(edge_segments(f.box, f.edge, 2.0, &uniform), 20.0);
  const auto a = edge_points(f.box, f.edge, 20, &uniform);
  const auto b = f.box.edge_points_by_length(f.edge, 20);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]);
  const auto t = graded_parameters(Vec3::Zero(), Vec3(1, 0, 0), 4, nullptr);
  EXPECT_EQ(t, (std::vector<double>{0, 0.25, 0.5, 0.75, 1}));
}

TEST(Sizing, GradedEdgeStartsAtTheLocalSizeAndGrows) {
  Fixture f;
  const core::SizeField field(f.box, 2.0, {{"Vertex1", 0.5}}, 0.3);
  // The integral of ds / min(2, 0.5 + 0.3 s) over 40: ln(4) / 0.3 up to s = 5, then 35 / 2.
  const double expected = std::log(4.0) / 0.3 + 35.0 / 2.0;
  const double n = edge_segments(f.box, f.edge, 2.0, &field);
  EXPECT_NEAR(n, expected, 0.02);
  const int count = int(std::lround(n));
  const auto p = edge_points(f.box, f.edge, count, &field);
  ASSERT_EQ(int(p.size()), count + 1);
  EXPECT_LT((p[0] - f.box.vertex_point(core::VertexId(1))).norm(), 1e-12);
  EXPECT_NEAR((p[1] - p[0]).norm(), 0.5, 0.1);
  EXPECT_NEAR((p[count] - p[count - 1]).norm(), 2.0, 0.2);
  for (int i = 1; i < count; ++i) {
    EXPECT_GE((p[i + 1] - p[i]).norm(), (p[i] - p[i - 1]).norm() - 1e-6);  // grows
    EXPECT_LT(f.box.distance_to_edge(f.edge, p[i]), 1e-9);                 // on the edge
  }
  const auto t = graded_parameters(f.box.vertex_point(core::VertexId(1)), p[count], count, &field);
  for (int i = 0; i <= count; ++i) EXPECT_NEAR(t[i] * 40, (p[i] - p[0]).norm(), 1e-3);
}

}  // namespace
}  // namespace vorohex::mesh::detail
