// The local size field (issue 21): exact at its entities, graded away from them, never above
// the global size; bad entries named.
#include "core/size_field.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "occ/primitives.h"

namespace vorohex::core {
namespace {

// The face of a 10 x 4 x 2 box at x = 0 (its id found by geometry, not assumed).
FaceId face_at_x0(const MeshDomain& box) {
  for (FaceId f : box.faces()) {
    const SurfaceInfo s = box.surface_info(f);
    if (s.kind == SurfaceKind::plane && std::abs(std::abs(s.direction.x()) - 1) < 1e-12 &&
        std::abs(box.project_to_face(f, Vec3(-5, 2, 1)).x()) < 1e-9)
      return f;
  }
  return FaceId();
}

TEST(SizeField, UniformWithoutSources) {
  const SizeField f(2.5);
  EXPECT_TRUE(f.uniform());
  EXPECT_DOUBLE_EQ(f.at(Vec3(100, -3, 7)), 2.5);
  EXPECT_DOUBLE_EQ(f.min_size(), 2.5);
  EXPECT_DOUBLE_EQ(f.segments_along({Vec3(0, 0, 0), Vec3(10, 0, 0)}), 4.0);
}

TEST(SizeField, LocalAtTheEntityGradedAwayCappedByTheGlobalSize) {
  const occ::Solid box = occ::make_box(10, 4, 2);
  const FaceId f = face_at_x0(box);
  ASSERT_TRUE(f.valid());
  const SizeField field(box, 2.0, {{entity_name(f), 0.5}}, 0.25);
  EXPECT_FALSE(field.uniform());
  EXPECT_DOUBLE_EQ(field.min_size(), 0.5);
  EXPECT_NEAR(field.at(Vec3(0, 2, 1)), 0.5, 1e-12);            // on the face
  EXPECT_NEAR(field.at(Vec3(2, 2, 1)), 0.5 + 0.25 * 2, 1e-9);  // 2 away
  EXPECT_NEAR(field.at(Vec3(9, 2, 1)), 2.0, 1e-12);            // capped at the global size
  // Along x from the face: the integral of ds / (0.5 + 0.25 s) up to s = 6, then 4 / 2.
  const double expected = std::log((0.5 + 0.25 * 6) / 0.5) / 0.25 + 4 / 2.0;
  std::vector<Vec3> line;
  for (int k = 0; k <= 1000; ++k) line.emplace_back(10.0 * k / 1000, 2, 1);
  EXPECT_NEAR(field.segments_along(line), expected, 1e-3);
}

TEST(SizeField, VertexAndEdgeSources) {
  const occ::Solid box = occ::make_box(10, 4, 2);
  const VertexId v(1);
  const EdgeId e(1);
  const SizeField field(box, 3.0, {{"Vertex1", 0.2}, {"Edge1", 1.0}}, 0.5);
  EXPECT_NEAR(field.at(box.vertex_point(v)), 0.2, 1e-12);
  const std::vector<Vec3> mid = box.edge_points_by_length(e, 2);
  EXPECT_LE(field.at(mid[1]), 1.0 + 1e-12);
  EXPECT_EQ(field.applied().size(), 2u);
}

TEST(SizeField, AnEntityNamedTwiceKeepsTheSmallerSize) {
  const occ::Solid box = occ::make_box(1, 1, 1);
  const SizeField field(box, 1.0, {{"Face1", 0.4}, {"Face1", 0.2}}, 0.3);
  ASSERT_EQ(field.applied().size(), 1u);
  EXPECT_DOUBLE_EQ(field.applied()[0].size, 0.2);
}

TEST(SizeField, ALocalSizeNotBelowTheGlobalOneIsAWarningAndNoSource) {
  const occ::Solid box = occ::make_box(1, 1, 1);
  const SizeField field(box, 0.5, {{"Face2", 0.8}}, 0.3);
  EXPECT_TRUE(field.uniform());
  ASSERT_EQ(field.diagnostics().size(), 1u);
  EXPECT_EQ(field.diagnostics()[0].code, "local_size_not_finer");
  EXPECT_EQ(field.diagnostics()[0].entities, std::vector<std::string>{"Face2"});
}

TEST(SizeField, BadEntriesAreNamed) {
  const occ::Solid box = occ::make_box(1, 1, 1);
  auto message = [&](const std::vector<LocalSize>& sizes, double grading = 0.3) {
    try {
      SizeField(box, 1.0, sizes, grading);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({{"Face7", 0.1}}).find("no Face7 (it has 6 faces)"), std::string::npos);
  EXPECT_NE(message({{"Edge13", 0.1}}).find("no Edge13 (it has 12 edges)"), std::string::npos);
  EXPECT_NE(message({{"Solid1", 0.1}}).find("'Solid1' is not an entity name"), std::string::npos);
  EXPECT_NE(message({{"Face0", 0.1}}).find("not an entity name"), std::string::npos);
  EXPECT_NE(message({{"Face1", -1}}).find("Face1 must be finite and > 0"), std::string::npos);
  EXPECT_NE(message({{"Face1", NAN}}).find("Face1 must be finite and > 0"), std::string::npos);
  EXPECT_NE(message({{"Face1", 0.1}}, 0).find("grading"), std::string::npos);
}

TEST(SizeField, EntityNamesParse) {
  char kind = 0;
  int id = 0;
  EXPECT_TRUE(parse_entity_name("Face12", kind, id));
  EXPECT_EQ(kind, 'f');
  EXPECT_EQ(id, 12);
  EXPECT_TRUE(parse_entity_name("Vertex3", kind, id));
  EXPECT_EQ(kind, 'v');
  EXPECT_FALSE(parse_entity_name("Face", kind, id));
  EXPECT_FALSE(parse_entity_name("Face1a", kind, id));
  EXPECT_FALSE(parse_entity_name("face1", kind, id));
  EXPECT_FALSE(parse_entity_name("Face-1", kind, id));
}

// Seen from a plane a prism is swept from: the smallest size over the given heights.
TEST(SizeField, ExtrudedViewTakesTheSmallestSizeOverTheHeights) {
  const occ::Solid box = occ::make_box(10, 4, 2);
  // Vertex1 is a corner of the box; find its height.
  const Vec3 v = box.vertex_point(VertexId(1));
  const SizeField field(box, 2.0, {{"Vertex1", 0.5}}, 0.25);
  const SizeField seen = field.extruded(Vec3::Zero(), Vec3::UnitZ(), {0.0, 1.0, 2.0});
  const Vec3 below(v.x(), v.y(), v.z() + 5);  // far above it: the view drops it onto a height
  EXPECT_GT(field.at(below), 1.5);
  EXPECT_NEAR(seen.at(below), 0.5, 1e-12);
}

}  // namespace
}  // namespace vorohex::core
