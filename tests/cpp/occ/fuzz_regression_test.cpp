// Inputs on which the fuzz targets of bench/fuzz found crashes or hangs, read again through
// the same entry points (bench/fuzz/README.md). OCCT's STEP and IGES translators dereferenced
// the references of entities that had failed to load (read_solid now refuses such files
// before the transfer); OCCT's BREP reader looped on a failed stream (it now throws).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "fixtures/diagnostics.h"
#include "occ/primitives.h"
#include "occ/shape_io.h"

namespace vorohex::occ {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "vorohex_fuzz_regression_" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// What fuzz_shape_reader does with its bytes: the two lowest bits of the first byte pick the
// entry point (BREP string, .step, .brep, .iges), bit 2 sets several_solids.
ReadResult read_like_fuzz_target(const std::string& bytes) {
  ReadOptions options;
  options.several_solids = (bytes[0] & 4) != 0;
  const std::string text = bytes.substr(1);
  switch (bytes[0] & 3) {
    case 0:
      return read_solid_from_brep_string(text, options);
    case 1:
      return read_solid(write_temp("input.step", text), options);
    case 2:
      return read_solid(write_temp("input.brep", text), options);
    default:
      return read_solid(write_temp("input.iges", text), options);
  }
}

TEST(FuzzRegression, ShapeReaderInputsAreRefused) {
  const fs::path dir = fs::path(VOROHEX_SOURCE_DIR) / "bench/fuzz/regressions/fuzz_shape_reader";
  ASSERT_TRUE(fs::is_directory(dir)) << dir;
  int inputs = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    SCOPED_TRACE(entry.path().filename().string());
    const std::string bytes = read_text(entry.path());
    ASSERT_FALSE(bytes.empty());
    const ReadResult r = read_like_fuzz_target(bytes);
    EXPECT_FALSE(r.ok());
    EXPECT_NE(testing::find_diagnostic(r.diagnostics, "unreadable_file"), nullptr);
    ++inputs;
  }
  EXPECT_GE(inputs, 10);
}

// The smallest form of those inputs: a LINE whose point is a DIRECTION (loaded with a null
// point: SIGSEGV in StepGeom_CartesianPoint::NbCoordinates) or a #id that does not exist.
TEST(FuzzRegression, StepEntityWithABrokenReferenceIsADamagedFile) {
  const std::string box = read_text(fs::path(VOROHEX_SOURCE_DIR) / "examples/box_3x2x1.step");
  const std::string line = "#27 = LINE('',#28,#29);";
  ASSERT_NE(box.find(line), std::string::npos);
  for (const char* broken : {"#27 = LINE('',#30,#29);", "#27 = LINE('',#9999,#29);"}) {
    SCOPED_TRACE(broken);
    std::string step = box;
    step.replace(step.find(line), line.size(), broken);
    const ReadResult r = read_solid(write_temp("broken_line.step", step));
    ASSERT_FALSE(r.ok());
    const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "unreadable_file");
    ASSERT_NE(d, nullptr);
    EXPECT_NE(d->message.find("damaged STEP file"), std::string::npos) << d->message;
    EXPECT_NE(d->message.find("#27 StepGeom_Line"), std::string::npos) << d->message;
  }
  // The untouched file still reads (metadata failures, as in HexMe's i12, are tolerated:
  // ReadSolid.HexMeModelsReadAsSolids).
  EXPECT_TRUE(read_solid(write_temp("box.step", box)).ok());
}

// BREP text cut after one of an edge's representations: the list ends at a 0 that never
// comes, and OCCT's reader went on reading the failed stream (a hang).
TEST(FuzzRegression, BrepTextEndingInsideAnEdgeIsUnreadable) {
  const std::string brep = make_box(1, 2, 3).to_brep_string();
  const std::size_t edge = brep.find("\nEd\n");
  ASSERT_NE(edge, std::string::npos);
  const std::size_t curve_on_surface = brep.find("\n2 ", edge);
  ASSERT_NE(curve_on_surface, std::string::npos);
  const std::string cut = brep.substr(0, brep.find('\n', curve_on_surface + 1) + 1);
  for (const ReadResult& r :
       {read_solid_from_brep_string(cut), read_solid(write_temp("cut.brep", cut))}) {
    ASSERT_FALSE(r.ok());
    const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "unreadable_file");
    ASSERT_NE(d, nullptr);
    EXPECT_NE(d->message.find("ends early"), std::string::npos) << d->message;
  }
  EXPECT_TRUE(read_solid_from_brep_string(brep).ok());
}

}  // namespace
}  // namespace vorohex::occ
