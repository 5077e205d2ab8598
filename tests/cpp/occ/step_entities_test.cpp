// STEP files whose entities fail to load (issue 19): a failure in an entity the shape does not
// need (a presentation style, a colour, a point marker) is a warning naming it, and the solid
// is read; a failure in an entity of the shape's geometry or topology stays an error.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "fixtures/diagnostics.h"
#include "occ/primitives.h"
#include "occ/shape_io.h"

namespace vorohex::occ {
namespace {

std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "vorohex_step_entities_" +
         ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" + name;
}

std::string box_step_text() {
  const std::string path = temp_path("box.step");
  std::string error;
  EXPECT_TRUE(write_solid(make_box(3, 2, 1), path, &error)) << error;
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Inserts entities just before the DATA section ends.
std::string with_entities(std::string text, const std::string& entities) {
  const std::size_t end = text.rfind("ENDSEC;");
  EXPECT_NE(end, std::string::npos);
  text.insert(end, entities);
  return text;
}

std::string write(const std::string& name, const std::string& text) {
  const std::string path = temp_path(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// Point styles whose marker is not a MARKER_SELECT but a colour (what Gmsh's benchmark
// universal joint holds 182 of: "illegal type"), assigned as CAD systems write styles.
const char* kBadPointStyles =
    "#90001 = COLOUR_RGB('',0.8,0.1,0.1);\n"
    "#90002 = POINT_STYLE('',#90001,POSITIVE_LENGTH_MEASURE(1.),#90001);\n"
    "#90003 = POINT_STYLE('',#90001,POSITIVE_LENGTH_MEASURE(2.),#90001);\n"
    "#90004 = PRESENTATION_STYLE_ASSIGNMENT((#90002,#90003));\n";

TEST(StepEntities, FailedPresentationEntitiesAreAWarningNamingThem) {
  const std::string path = write("styled.step", with_entities(box_step_text(), kBadPointStyles));
  const ReadResult r = read_solid(path);
  ASSERT_TRUE(r.ok()) << (r.diagnostics.empty() ? "" : format(r.diagnostics[0]));
  EXPECT_NEAR(r.solid->volume(), 6.0, 1e-9);
  const core::Diagnostic* w = testing::find_diagnostic(r.diagnostics, "ignored_entities");
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->severity, core::Severity::warning);
  EXPECT_NE(w->message.find("StepVisual_PointStyle"), std::string::npos) << w->message;
  EXPECT_NE(w->message.find("2 entities"), std::string::npos) << w->message;
  EXPECT_NE(w->message.find("#90002"), std::string::npos) << w->message;
  EXPECT_EQ(testing::find_diagnostic(r.diagnostics, "unreadable_file"), nullptr);
}

// A unit with a wrong parameter count (as in HexMe's i12): the representation context refers
// to it, but units are metadata the translator copes with, so the file is read.
TEST(StepEntities, AFailedUnitOfTheContextIsAWarning) {
  std::string text = box_step_text();
  const std::string unit = "SI_UNIT($,.STERADIAN.)";
  const std::size_t at = text.find(unit);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, unit.size(), "SI_UNIT(.STERADIAN.)");
  const ReadResult r = read_solid(write("unit.step", text));
  ASSERT_TRUE(r.ok()) << (r.diagnostics.empty() ? "" : format(r.diagnostics[0]));
  EXPECT_NEAR(r.solid->volume(), 6.0, 1e-9);
  const core::Diagnostic* w = testing::find_diagnostic(r.diagnostics, "ignored_entities");
  ASSERT_NE(w, nullptr);
  EXPECT_NE(w->message.find("StepBasic_SiUnitAndSolidAngleUnit"), std::string::npos) << w->message;
}

TEST(StepEntities, AFileWithoutFailuresHasNoWarning) {
  const ReadResult r = read_solid(write("plain.step", box_step_text()));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(testing::find_diagnostic(r.diagnostics, "ignored_entities"), nullptr);
}

TEST(StepEntities, FailedGeometryIsStillUnreadable) {
  // A point of the box's geometry whose coordinates are not numbers.
  std::string text = box_step_text();
  const std::string point = "CARTESIAN_POINT('',";
  const std::size_t open = text.find(point) + point.size();
  ASSERT_GT(open, point.size());
  const std::size_t close = text.find(')', open);
  text.replace(open, close - open + 1, "('x','y','z')");
  const ReadResult r = read_solid(write("broken_point.step", text));
  EXPECT_FALSE(r.ok());
  const core::Diagnostic* e = testing::find_diagnostic(r.diagnostics, "unreadable_file");
  ASSERT_NE(e, nullptr);
  EXPECT_NE(e->message.find("StepGeom_CartesianPoint"), std::string::npos) << e->message;
}

TEST(StepEntities, APresentationEntityThatGeometryRefersToIsNeeded) {
  // Whatever its type, an entity that a geometric entity refers to is needed: an axis
  // placement whose location is a failed colour would reach the translator as null.
  std::string text = box_step_text();
  const std::size_t axis = text.find("AXIS2_PLACEMENT_3D('',#");
  ASSERT_NE(axis, std::string::npos);
  const std::size_t ref = axis + std::string("AXIS2_PLACEMENT_3D('',").size();
  const std::size_t comma = text.find(',', ref);
  text.replace(ref, comma - ref, "#90005");
  text = with_entities(text, "#90005 = COLOUR_RGB('',0.1,'green',0.1);\n");
  const ReadResult r = read_solid(write("referenced_colour.step", text));
  EXPECT_FALSE(r.ok());
  EXPECT_NE(testing::find_diagnostic(r.diagnostics, "unreadable_file"), nullptr);
}

}  // namespace
}  // namespace vorohex::occ
