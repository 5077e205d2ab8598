// What the meshers ask of local sizes (mesh/detail/sizing.h): counts and node spacing along
// an edge follow the field; without local sizes they are exactly the uniform ones.
#include "mesh/detail/sizing.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/face_cusp.h"
#include "fixtures/machined.h"
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

// A face that comes to a point (a plate's top around a boss tangent to the plate's outline
// from inside: a crescent): with nodes at equal spacing the quad at the point has the angle
// of the chords to the first nodes, about size / (2 r) radians for a line and a circle. Here
// both edges curve the same way: the boss's circle (radius 10) opens the corner as its chord
// lengthens, the outline's (radius 20) closes it. The boss's segment at the point is
// lengthened until the chords open to asin(0.3) (at most three segments' worth); the
// outline's is shortened (two of its nodes where the boss has one: the quad mesher's ladder
// at the point), and its second node goes far enough that the ladder's quad turns by
// asin(0.3) at the first (its corner there: 180 degrees less that), at most 4.5 segments'
// worth and 1.4 times the boss's first (graded by 1.5 from the first, the turn stayed near
// 9 degrees). An edge with no point at its ends is as before.
TEST(Sizing, SegmentsNextToAPointOpenItsCorner) {
  const occ::Solid s = testing::fuse(occ::make_cylinder(20, 4, Vec3::Zero(), testing::kZ),
                                     occ::make_cylinder(10, 12, Vec3(10, 0, 0), testing::kZ));
  std::vector<core::Cusp> cusps;
  for (core::FaceId f : s.faces())
    for (const core::Cusp& c : core::face_cusps(s, f)) cusps.push_back(c);
  ASSERT_FALSE(cusps.empty());
  const core::Cusp& c = cusps.front();
  // The segments from the point: the wire runs into it along `in`, out of it along `out`.
  auto from_point = [&](const core::OrientedEdge& oe, int n, bool into) {
    std::vector<Vec3> p = edge_points(s, oe.edge, n, nullptr);
    if (oe.forward == into) std::reverse(p.begin(), p.end());
    EXPECT_LT((p[0] - s.vertex_point(c.vertex)).norm(), 1e-9);
    std::vector<double> segments;
    for (int i = 0; i < n; ++i) segments.push_back((p[i + 1] - p[i]).norm());
    return segments;
  };
  const double l_in = s.edge_length(c.in.edge), l_out = s.edge_length(c.out.edge);
  const int n_in = int(std::lround(l_in / 2)), n_out = int(std::lround(l_out / 2));
  const std::vector<double> in = from_point(c.in, n_in, true),
                            out = from_point(c.out, n_out, false);
  const bool in_is_outline = l_in > l_out;  // the outline's circle is the longer
  const std::vector<double>& outline = in_is_outline ? in : out;
  const std::vector<double>& boss = in_is_outline ? out : in;
  const double outline_mean = std::max(l_in, l_out) / (in_is_outline ? n_in : n_out);
  const double boss_mean = std::min(l_in, l_out) / (in_is_outline ? n_out : n_in);
  EXPECT_GT(boss[0], 1.2 * boss_mean);
  EXPECT_LT(outline[0], 0.8 * outline_mean);
  // The turn at the outline's first node: on its circle (radius 20) about the second
  // node's distance over 2 r. Here the boss's first node bounds it (1.4 times that, about):
  // over 0.2 radians (the quad's corner there has a sine above 0.2), where graded by 1.5
  // from the first it was 0.06.
  const double second = outline[0] + outline[1];
  EXPECT_GT(second / 40, 0.2);
  EXPECT_GT(second, 1.3 * boss[0]);
  EXPECT_LE(second, 4.5 * outline_mean);
  // The corner is open, and much wider than with equal segments of the mean.
  const double angle = core::cusp_signed_angle(s, c, in[0], out[0]);
  const double equal = core::cusp_signed_angle(s, c, in_is_outline ? outline_mean : boss_mean,
                                               in_is_outline ? boss_mean : outline_mean);
  EXPECT_GT(angle, 0.1);
  EXPECT_GT(angle, 2 * equal);
  // An edge with no point at either end keeps its equal spacing.
  for (core::EdgeId e : s.edges()) {
    if (e == c.in.edge || e == c.out.edge || s.edge_is_degenerated(e)) continue;
    bool at_point = false;
    for (const core::Cusp& k : cusps)
      at_point =
          at_point || k.vertex == s.edge_first_vertex(e) || k.vertex == s.edge_last_vertex(e);
    if (at_point) continue;
    const auto p = edge_points(s, e, 8, nullptr);
    const auto q = s.edge_points_by_length(e, 8);
    for (std::size_t i = 0; i < p.size(); ++i) EXPECT_LT((p[i] - q[i]).norm(), 1e-12);
  }
}

}  // namespace
}  // namespace vorohex::mesh::detail
