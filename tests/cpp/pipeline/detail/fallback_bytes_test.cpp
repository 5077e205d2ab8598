#include "pipeline/detail/fallback_bytes.h"

#include <gtest/gtest.h>

#include <string>

namespace vorohex::pipeline::detail {
namespace {

// What crosses from the child that computed the fallback comes back as it was: the mesh
// (points bit for bit, node classes, sub-volumes), the diagnostics, the stats and the
// composites; the check, groups and per-hex Jacobians are the caller's to recompute.
TEST(FallbackBytes, AResultComesBackAsItWas) {
  MeshResult r;
  r.ok = true;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i)
        r.mesh.add_node({i * 0.1 + 1e-17, j / 3.0, k * 7.25},
                        k ? core::NodeClass::on(core::FaceId(2 + i)) : core::NodeClass::interior());
  r.mesh.add_hex({0, 1, 4, 3, 6, 7, 10, 9}, 1);
  r.mesh.add_hex({1, 2, 5, 4, 7, 8, 11, 10}, 2);
  // Second order: the mid-edge nodes of each hex (here any nodes, for the bytes' sake).
  r.mesh.set_mid_edge_nodes(
      {{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}, {11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0}});
  r.stats.size_used = 0.3;
  r.stats.intervals = {1, 2, 3};
  r.stats.seconds_meshing = 1.5, r.stats.seconds_smoothing = 2.5, r.stats.seconds_checking = 0.1;
  r.stats.min_sj_before_smoothing = -0.25, r.stats.mean_sj_before_smoothing = 0.75;
  r.stats.sub_volumes = 2;
  r.stats.scheme = "grid";
  r.stats.sub_volume_schemes = {"grid", "grid"};
  r.stats.sub_volume_types = {"-", "-"};
  r.stats.absorbed_deviation = 0.05;
  r.stats.local_sizes = {{"Face3", 0.1}};
  r.diagnostics = {core::make_warning("fallback", std::string("why\x1f(why)\x1f and \0 more", 27),
                                      {"Face1", "Edge2"}),
                   core::make_error("inverted_elements", "2 hexahedra")};
  r.absorbed.absorbed_face = {0, 1, 0};
  r.absorbed.absorbed_edge = {0, 0, 1, 1};
  r.absorbed.composite_of_face = {-1, 0, -1};
  r.absorbed.composites = {{core::FaceId(2), {core::FaceId(2), core::FaceId(1)}}};
  r.absorbed.small = 0.025;
  r.absorbed.samples = {{1, 2, 3}};
  r.absorbed.face_boxes = {{{0, 0, 0}, {1, 1, 1}}, {{-1, -2, -3}, {4, 5, 6}}};

  const std::string bytes = fallback_to_bytes(r, true);
  MeshResult back;
  bool second = false;
  ASSERT_TRUE(fallback_from_bytes(bytes, back, second));
  EXPECT_TRUE(second);
  EXPECT_TRUE(back.ok);
  ASSERT_EQ(back.mesh.num_nodes(), r.mesh.num_nodes());
  for (std::size_t n = 0; n < r.mesh.num_nodes(); ++n) {
    EXPECT_EQ(back.mesh.points()[n], r.mesh.points()[n]);
    EXPECT_EQ(back.mesh.node_classes()[n], r.mesh.node_classes()[n]);
  }
  EXPECT_EQ(back.mesh.hexes(), r.mesh.hexes());
  EXPECT_EQ(back.mesh.sub_volumes(), r.mesh.sub_volumes());
  EXPECT_EQ(back.mesh.order(), 2);
  EXPECT_EQ(back.mesh.mid_edge_nodes(), r.mesh.mid_edge_nodes());
  EXPECT_EQ(back.stats.size_used, 0.3);
  EXPECT_EQ(back.stats.intervals, r.stats.intervals);
  EXPECT_EQ(back.stats.seconds_smoothing, 2.5);
  EXPECT_EQ(back.stats.min_sj_before_smoothing, -0.25);
  EXPECT_EQ(back.stats.sub_volumes, 2);
  EXPECT_EQ(back.stats.scheme, "grid");
  EXPECT_EQ(back.stats.sub_volume_schemes, r.stats.sub_volume_schemes);
  EXPECT_EQ(back.stats.sub_volume_types, r.stats.sub_volume_types);
  EXPECT_EQ(back.stats.absorbed_deviation, 0.05);
  ASSERT_EQ(back.stats.local_sizes.size(), 1u);
  EXPECT_EQ(back.stats.local_sizes[0].entity, "Face3");
  ASSERT_EQ(back.diagnostics.size(), 2u);
  EXPECT_EQ(back.diagnostics[0].severity, core::Severity::warning);
  EXPECT_EQ(back.diagnostics[0].message, r.diagnostics[0].message);
  EXPECT_EQ(back.diagnostics[0].entities, r.diagnostics[0].entities);
  EXPECT_EQ(back.diagnostics[1].code, "inverted_elements");
  EXPECT_EQ(back.absorbed.absorbed_face, r.absorbed.absorbed_face);
  EXPECT_EQ(back.absorbed.absorbed_edge, r.absorbed.absorbed_edge);
  EXPECT_EQ(back.absorbed.composite_of_face, r.absorbed.composite_of_face);
  ASSERT_EQ(back.absorbed.composites.size(), 1u);
  EXPECT_EQ(back.absorbed.composites[0].name(), "Face2+Face1");
  EXPECT_EQ(back.absorbed.small, 0.025);
  EXPECT_EQ(back.absorbed.samples, r.absorbed.samples);
  ASSERT_EQ(back.absorbed.face_boxes.size(), 2u);
  EXPECT_EQ(back.absorbed.face_boxes[1].min, r.absorbed.face_boxes[1].min);
  EXPECT_EQ(back.absorbed.face_boxes[1].max, r.absorbed.face_boxes[1].max);
}

// Bytes that are not a fallback's result (a truncated pipe, another program's output) are
// refused, never read past their end.
TEST(FallbackBytes, TruncatedOrForeignBytesAreRefused) {
  MeshResult r;
  r.mesh.add_node({0, 0, 0});
  r.diagnostics = {core::make_info("grid", "a grid")};
  const std::string bytes = fallback_to_bytes(r, false);
  MeshResult back;
  bool second = true;
  ASSERT_TRUE(fallback_from_bytes(bytes, back, second));
  EXPECT_FALSE(second);
  for (std::size_t cut : {std::size_t(0), std::size_t(3), bytes.size() / 2, bytes.size() - 1})
    EXPECT_FALSE(fallback_from_bytes(bytes.substr(0, cut), back, second)) << cut;
  EXPECT_FALSE(fallback_from_bytes(bytes + "x", back, second));
  EXPECT_FALSE(fallback_from_bytes(std::string(bytes.size(), '\xff'), back, second));
}

}  // namespace
}  // namespace vorohex::pipeline::detail
