// Inputs on which the fuzz targets of bench/fuzz found crashes or hangs, read again through
// the same entry points (bench/fuzz/README.md). OCCT's STEP and IGES translators dereferenced
// the references of entities that had failed to load (read_solid now refuses such files
// before the transfer); OCCT's BREP reader looped on a failed stream (it now throws); broken
// BREP geometry and IGES files out of order crashed OCCT's check and parser.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

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

// Named after the running test too: ctest runs the tests as processes side by side.
std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "vorohex_fuzz_regression_" +
                           ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
                           name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// What fuzz_shape_reader does with its bytes: the two lowest bits of the first byte pick the
// entry point (BREP string, .step, .brep, .iges), bit 2 sets several_solids.
ReadResult read_like_fuzz_target(const std::string& bytes) {
  ReadOptions options;
  options.several_solids = (bytes[0] & 4) != 0;
  options.repair_time_limit = 5;  // as the target sets it
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
    EXPECT_TRUE(testing::find_diagnostic(r.diagnostics, "unreadable_file") ||
                testing::find_diagnostic(r.diagnostics, "invalid_shape"));
    ++inputs;
  }
  EXPECT_GE(inputs, 10);
}

// BREP text whose trimmed, offset, extrusion or revolution geometry has a basis of an
// unknown type: OCCT's reader dereferenced the null basis (SIGSEGV). The text is read in a
// child process first; the crash is named, the test (and a FreeCAD session) goes on.
TEST(FuzzRegression, BrepGeometryWithoutItsBasisCrashesOnlyAChildProcess) {
  const fs::path dir = fs::path(VOROHEX_SOURCE_DIR) / "bench/fuzz/regressions/fuzz_shape_reader";
  int inputs = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.find("null_basis") == std::string::npos) continue;
    SCOPED_TRACE(name);
    const ReadResult r = read_like_fuzz_target(read_text(entry.path()));
    ASSERT_FALSE(r.ok());
    const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "unreadable_file");
    ASSERT_NE(d, nullptr);
    EXPECT_NE(d->message.find("BREP reader crashed on it (the computation crashed with SIG"),
              std::string::npos)
        << d->message;
    ++inputs;
  }
  EXPECT_EQ(inputs, 7);
  EXPECT_TRUE(read_solid_from_brep_string(make_box(1, 2, 3).to_brep_string()).ok());
}

// Damaged BREP solids on which OCCT's shape healing classified points without end
// (BRepTopAdaptor_FClass2d::Perform < ShapeFix_Solid::SolidFromShell): the repair runs in a
// child process that is stopped at the time limit; the solid is refused, naming why.
TEST(FuzzRegression, ARepairThatNeverEndsIsStoppedAtItsTimeLimit) {
  const fs::path dir = fs::path(VOROHEX_SOURCE_DIR) / "bench/fuzz/regressions/fuzz_shape_reader";
  int inputs = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.find("hang_in_shapefix") == std::string::npos) continue;
    SCOPED_TRACE(name);
    const ReadResult r = read_like_fuzz_target(read_text(entry.path()));
    ASSERT_FALSE(r.ok());
    const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "invalid_shape");
    ASSERT_NE(d, nullptr);
    EXPECT_NE(d->message.find("did not finish within 5 s"), std::string::npos) << d->message;
    ++inputs;
  }
  EXPECT_EQ(inputs, 2);
}

// The smallest form of those inputs: a LINE whose point is a DIRECTION (loaded with a null
// point: SIGSEGV in StepGeom_CartesianPoint::NbCoordinates).
TEST(FuzzRegression, StepEntityWithAReferenceOfTheWrongTypeIsADamagedFile) {
  const std::string box = read_text(fs::path(VOROHEX_SOURCE_DIR) / "examples/box_3x2x1.step");
  const std::string line = "#27 = LINE('',#28,#29);";
  ASSERT_NE(box.find(line), std::string::npos);
  std::string step = box;
  step.replace(step.find(line), line.size(), "#27 = LINE('',#30,#29);");
  const ReadResult r = read_solid(write_temp("broken_line.step", step));
  ASSERT_FALSE(r.ok());
  const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "unreadable_file");
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find("damaged STEP file"), std::string::npos) << d->message;
  EXPECT_NE(d->message.find("#27 StepGeom_Line"), std::string::npos) << d->message;
  // The untouched file still reads (metadata failures, as in HexMe's i12, are tolerated:
  // ReadSolid.HexMeModelsReadAsSolids).
  EXPECT_TRUE(read_solid(write_temp("box.step", box)).ok());
}

// STEP files giving one instance name to two entities (OCCT resolved their references over
// arrays it does not initialise and, depending on the heap, never ended) or referring to a
// name they never give or to their own (OCCT's own check of such a file recursed without
// end, StepShape_OrientedEdge::EdgeStart); a string that is never closed would hide such
// references from the scan.
TEST(FuzzRegression, StepNamesGivenTwiceOrNeverAreADamagedFile) {
  const std::string box = read_text(fs::path(VOROHEX_SOURCE_DIR) / "examples/box_3x2x1.step");
  const std::string direction = "#30 = DIRECTION('',(0.,0.,1.));";
  const std::string line = "#27 = LINE('',#28,#29);";
  ASSERT_NE(box.find(direction), std::string::npos);
  ASSERT_NE(box.find(line), std::string::npos);
  std::string twice = box, never = box, itself = box, unclosed = box;
  twice.replace(twice.find(direction), 3, "#28");
  never.replace(never.find(line), line.size(), "#27 = LINE('',#9999,#29);");
  itself.replace(itself.find(line), line.size(), "#27 = LINE('',#27,#29);");
  unclosed.replace(unclosed.find(line), line.size(), "#27 = LINE(',#28,#29);");
  for (const auto& [step, what] : {std::pair{twice, "the name #28 is given twice"},
                                   std::pair{never, "refers to #9999, which it never gives"},
                                   std::pair{itself, "#27 refers to itself"},
                                   std::pair{unclosed, "a string or a comment is never closed"}}) {
    const ReadResult r = read_solid(write_temp("names.step", step));
    ASSERT_FALSE(r.ok());
    const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "unreadable_file");
    ASSERT_NE(d, nullptr);
    EXPECT_NE(d->message.find(what), std::string::npos) << d->message;
  }
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

// BREP text whose face refers to a surface, or whose edge to a curve, that does not exist:
// the face or edge is read without geometry, and OCCT's validity check dereferenced it
// (BRepCheck_Edge::InContext).
TEST(FuzzRegression, BrepFaceOrEdgeWithoutGeometryIsInvalid) {
  const std::string brep = make_box(1, 2, 3).to_brep_string();
  // The first face's "<natural restriction> <tolerance> <surface> <location>" line, and
  // the first edge's 3D curve line "1 <curve> <location> <first> <last>".
  const std::size_t face = brep.find("\nFa\n");
  const std::size_t edge = brep.find("\nEd\n");
  ASSERT_NE(face, std::string::npos);
  ASSERT_NE(edge, std::string::npos);
  const std::size_t surface_line = face + 4, curve_line = brep.find('\n', edge + 4) + 1;
  ASSERT_EQ(brep.compare(curve_line, 3, "1  "), 0) << brep.substr(curve_line, 20);
  std::string no_surface = brep, no_curve = brep;
  no_surface.replace(surface_line, brep.find('\n', surface_line) - surface_line, "0 1e-07 99 0");
  no_curve.replace(curve_line, brep.find('\n', curve_line) - curve_line, "1  99 0 0 1");
  for (const std::string& text : {no_surface, no_curve}) {
    const ReadResult r = read_solid_from_brep_string(text);
    ASSERT_FALSE(r.ok());
    const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "invalid_shape");
    ASSERT_NE(d, nullptr);
    EXPECT_NE(d->message.find("without surface or edges without curve"), std::string::npos)
        << d->message;
    EXPECT_EQ(d->entities.size(), 1u);
  }
}

// IGES files whose parameter lines come before the directory, read after another IGES file:
// OCCT's parser filed them under the previous file's freed entries (iges_newparam). It cuts
// the text into 80-column records, so a longer line can do the same.
TEST(FuzzRegression, IgesFilesNotInOrderedRecordsAreRefused) {
  const fs::path seed =
      fs::path(VOROHEX_SOURCE_DIR) / "bench/fuzz/corpus/fuzz_shape_reader/box.iges";
  const std::string iges = read_text(seed).substr(1);  // without the selector byte
  std::vector<std::string> lines;
  std::istringstream in(iges);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  const auto section = [](const std::string& line) { return line.size() > 72 ? line[72] : ' '; };
  const auto first_d = std::find_if(lines.begin(), lines.end(),
                                    [&](const std::string& l) { return section(l) == 'D'; });
  const auto first_p = std::find_if(lines.begin(), lines.end(),
                                    [&](const std::string& l) { return section(l) == 'P'; });
  ASSERT_TRUE(first_d != lines.end() && first_p != lines.end());
  std::vector<std::string> p_before_d(lines.begin(), first_d), long_line = lines;
  p_before_d.push_back(*first_p);
  for (auto it = first_d; it != lines.end(); ++it)
    if (it != first_p) p_before_d.push_back(*it);
  long_line[first_d - lines.begin()] += "0000000000";
  const auto text = [](const std::vector<std::string>& ls) {
    std::string t;
    for (const std::string& l : ls) t += l + "\n";
    return t;
  };

  // The seed (FreeCAD's IGES export of a box: 6 faces, no solid) parses and leaves the state.
  const ReadResult box = read_solid(write_temp("box.iges", iges));
  EXPECT_NE(testing::find_diagnostic(box.diagnostics, "no_solid"), nullptr);
  for (const std::string& broken : {text(p_before_d), text(long_line)}) {
    const ReadResult r = read_solid(write_temp("broken.iges", broken));
    ASSERT_FALSE(r.ok());
    const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "unreadable_file");
    ASSERT_NE(d, nullptr);
    EXPECT_NE(d->message.find("damaged IGES file"), std::string::npos) << d->message;
  }
}

}  // namespace
}  // namespace vorohex::occ
