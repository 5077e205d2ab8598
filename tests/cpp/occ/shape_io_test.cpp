#include "occ/shape_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "fixtures/diagnostics.h"
#include "occ/detail/fixtures.h"
#include "occ/primitives.h"
#include "occ/split_solid.h"

namespace vorohex::occ {
namespace {

// Named after the running test too: ctest runs the tests as processes side by side.
std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "vorohex_occ_" +
         ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" + name;
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// The one error of a failed read.
core::Diagnostic only_error(const ReadResult& r) {
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.diagnostics.size(), 1u);
  return r.diagnostics.empty() ? core::Diagnostic{} : r.diagnostics.front();
}

TEST(ReadSolid, MissingFileIsFileNotFound) {
  const std::string path = temp_path("does_not_exist.step");
  std::remove(path.c_str());
  const ReadResult r = read_solid(path);
  const auto d = only_error(r);
  EXPECT_EQ(d.code, "file_not_found");
  EXPECT_NE(d.message.find("does not exist"), std::string::npos);
  EXPECT_NE(d.message.find(path), std::string::npos);
}

TEST(ReadSolid, EmptyAndWhitespaceFilesAreEmptyFile) {
  for (const std::string text : {"", "  \n\t \n"}) {
    const std::string path = temp_path("empty.step");
    write_text(path, text);
    const auto d = only_error(read_solid(path));
    EXPECT_EQ(d.code, "empty_file");
    EXPECT_NE(d.message.find("is empty"), std::string::npos);
  }
}

TEST(ReadSolid, TextFileNamedStepIsUnreadable) {
  const std::string path = temp_path("x.step");
  write_text(path, "this is not a STEP file\nat all\n");
  const auto d = only_error(read_solid(path));
  EXPECT_EQ(d.code, "unreadable_file");
  EXPECT_NE(d.message.find("not a readable STEP file"), std::string::npos);
  // Where the STEP parser stopped, as it says it (it printed it in red on stdout before).
  EXPECT_NE(d.message.find("the reader: StepFile : Undefined Parsing: Line 2: Incorrect syntax"),
            std::string::npos)
      << d.message;
}

TEST(ReadSolid, GarbageBrepIsUnreadable) {
  const std::string path = temp_path("x.brep");
  write_text(path, "DBRep_DrawableShape\nCASCADE Topology V1\nLocations 5\n1 2 3\n");
  EXPECT_EQ(only_error(read_solid(path)).code, "unreadable_file");
}

TEST(ReadSolid, UnsupportedExtensionIsNamed) {
  const std::string path = temp_path("part.stl");
  write_text(path, "solid x\nendsolid x\n");
  const auto d = only_error(read_solid(path));
  EXPECT_EQ(d.code, "unsupported_format");
  EXPECT_NE(d.message.find("'.stl'"), std::string::npos);
}

TEST(ReadSolid, OpenShellNamesItsFreeEdges) {
  const std::string path = temp_path("open_shell.brep");
  ASSERT_TRUE(detail::write_fixture(detail::Fixture::open_box_shell, path));
  const auto d = only_error(read_solid(path));
  EXPECT_EQ(d.code, "open_shell");
  EXPECT_NE(d.message.find("not closed"), std::string::npos);
  EXPECT_NE(d.message.find("4 edges"), std::string::npos);
  ASSERT_EQ(d.entities.size(), 4u);  // the border of the missing face
  for (const auto& e : d.entities) EXPECT_EQ(e.rfind("Edge", 0), 0u);
}

TEST(ReadSolid, TwoBoxesInOneStepAreSeveralSolids) {
  const std::string path = temp_path("two_boxes.step");
  ASSERT_TRUE(detail::write_fixture(detail::Fixture::two_boxes, path));
  const auto d = only_error(read_solid(path));
  EXPECT_EQ(d.code, "several_solids");
  EXPECT_NE(d.message.find("contains 2 solids; this command takes one solid"), std::string::npos);
}

// With several_solids (meshing), disjoint solids stay apart and touching ones are glued: the
// face they have in common becomes one face of both.
TEST(ReadSolid, SeveralSolidsAreGluedAtTheirCommonFaces) {
  ReadOptions several;
  several.several_solids = true;
  struct Case {
    detail::Fixture kind;
    int faces, interface_faces;
    double volume;
  };
  for (const Case& c :
       {Case{detail::Fixture::two_boxes, 12, 0, 2}, Case{detail::Fixture::touching_boxes, 11, 1, 2},
        Case{detail::Fixture::stacked_boxes, 13, 1, 3}}) {
    const std::string path = temp_path("several.brep");
    ASSERT_TRUE(detail::write_fixture(c.kind, path));
    const ReadResult r = read_solid(path, several);
    ASSERT_TRUE(r.ok()) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics[0]));
    EXPECT_EQ(r.solid->num_solids(), 2);
    // The stacked big box's top face is split where the unit box stands on it (3 faces):
    // 8 + 6 faces, one of them common.
    EXPECT_EQ(r.solid->num_faces(), c.faces);
    EXPECT_EQ(r.solid->num_interface_faces(), c.interface_faces);
    EXPECT_NEAR(r.solid->volume(), c.volume, 1e-9);
    bool said = false;
    for (const auto& d : r.diagnostics) said = said || d.code == "several_solids";
    EXPECT_TRUE(said);
    // Every entity of each part has its id in the whole; the shared face is the same id.
    std::vector<int> seen(r.solid->num_faces() + 1, 0);
    for (int k = 0; k < 2; ++k) {
      const Solid part = r.solid->part(k);
      EXPECT_EQ(part.num_solids(), 1);
      for (int dim = 0; dim < 3; ++dim)
        for (std::size_t i = 1; i < r.solid->part_ids(part, dim).size(); ++i)
          EXPECT_GT(r.solid->part_ids(part, dim)[i], 0);
      for (int f : r.solid->part_ids(part, 2)) ++seen[f];
    }
    int shared = 0;
    for (int f = 1; f <= r.solid->num_faces(); ++f) {
      EXPECT_EQ(seen[f] == 2, r.solid->face_is_interface(FaceId(f))) << "face " << f;
      shared += seen[f] == 2;
    }
    EXPECT_EQ(shared, c.interface_faces);
  }
  EXPECT_THROW(read_solid(temp_path("several.brep"), several).solid->part(2), std::out_of_range);
}

TEST(ReadSolid, OverlappingSolidsAreRefused) {
  ReadOptions several;
  several.several_solids = true;
  const std::string path = temp_path("overlap.brep");
  ASSERT_TRUE(detail::write_fixture(detail::Fixture::overlapping_boxes, path));
  const auto d = only_error(read_solid(path, several));
  EXPECT_EQ(d.code, "overlapping_solids");
  EXPECT_NE(d.message.find("overlap"), std::string::npos);
}

// A solid inside another: the general fuse gives as many solids (the inner one and the
// outer with a cavity), so only the volume shows the overlap. The volumes are compared to
// the integration's error plus a skin of the modelling tolerance over the faces (about
// 1e-6 here), far below the inner box's volume.
TEST(GlueSolids, ASolidInsideAnotherIsRefusedByItsVolume) {
  const Solid outer = make_box(10, 10, 10);
  const Solid inner = make_box(1, 1, 1, core::Vec3(4, 4, 4));
  const auto d = only_error(glue_solids({&outer, &inner}, "The pieces"));
  EXPECT_EQ(d.code, "overlapping_solids");
  // The fuse keeps two solids (the inner one's volume is cut out of the outer): what shows
  // the overlap is the volume.
  EXPECT_NE(d.message.find("glued, their volume is 1000 instead of 1001"), std::string::npos)
      << d.message;
  // Touching, not overlapping: glued.
  const Solid beside = make_box(1, 1, 1, core::Vec3(10, 4, 4));
  const ReadResult glued = glue_solids({&outer, &beside}, "The pieces");
  EXPECT_TRUE(glued.ok());
}

// Two boxes touching along an edge: refused by default (non_manifold); glued when the
// manifold check is off, as the plane cuts do for a neighbourhood of their pieces (the pieces
// that join the two by faces lie outside it). The overlap check can be skipped likewise; an
// overlap the fuse itself shows (more solids than given) is still refused.
TEST(GlueSolids, TheManifoldAndOverlapChecksCanBeLeftOut) {
  const Solid a = make_box(1, 1, 1);
  const Solid b = make_box(1, 1, 1, core::Vec3(1, 1, 0));
  EXPECT_EQ(only_error(glue_solids({&a, &b}, "The pieces")).code, "non_manifold");
  GlueOptions o;
  o.check_manifold = false;
  const ReadResult glued = glue_solids({&a, &b}, "The pieces", o);
  ASSERT_TRUE(glued.ok());
  EXPECT_EQ(glued.solid->num_solids(), 2);
  o.check_overlap = false;
  const Solid outer = make_box(10, 10, 10);
  const Solid crossing = make_box(2, 2, 2, core::Vec3(9, 4, 4));
  EXPECT_EQ(only_error(glue_solids({&outer, &crossing}, "The pieces", o)).code,
            "overlapping_solids");
}

// Solids that only touch (pieces of one split): OCCT's gluing mode skips intersecting their
// faces, and glues them as the full general fuse does: a block standing on part of a
// plate's face splits that face, and the two share one face.
TEST(GlueSolids, SolidsThatOnlyTouchAreGluedAsByTheFullFuse) {
  const Solid plate = make_box(10, 10, 1);
  const Solid block = make_box(2, 3, 4, core::Vec3(4, 3, 1));
  const Solid side = make_box(1, 10, 1, core::Vec3(10, 0, 0));
  GlueOptions touching;
  touching.only_touching = true;
  const ReadResult full = glue_solids({&plate, &block, &side}, "The pieces");
  const ReadResult glued = glue_solids({&plate, &block, &side}, "The pieces", touching);
  ASSERT_TRUE(full.ok());
  ASSERT_TRUE(glued.ok());
  EXPECT_EQ(glued.solid->num_solids(), 3);
  EXPECT_EQ(glued.solid->num_interface_faces(), full.solid->num_interface_faces());
  EXPECT_EQ(glued.solid->num_interface_faces(), 2);
  EXPECT_EQ(glued.solid->num_faces(), full.solid->num_faces());
  EXPECT_EQ(glued.solid->num_edges(), full.solid->num_edges());
  EXPECT_NEAR(glued.solid->volume(), 10 * 10 + 2 * 3 * 4 + 10, 1e-9);
}

// Solids touching along an edge or at a vertex only: one mesh of them would not be a
// manifold there, so the input is refused naming where they touch.
TEST(ReadSolid, SolidsTouchingAlongAnEdgeOrAtAVertexAreNonManifold) {
  ReadOptions several;
  several.several_solids = true;
  for (const auto& [kind, what] : {std::pair{detail::Fixture::edge_touching_boxes, "Edge"},
                                   std::pair{detail::Fixture::vertex_touching_boxes, "Vertex"}}) {
    SCOPED_TRACE(what);
    const std::string path = temp_path("pinched.brep");
    ASSERT_TRUE(detail::write_fixture(kind, path));
    const ReadResult r = read_solid(path, several);
    ASSERT_FALSE(r.ok());
    ASSERT_FALSE(r.diagnostics.empty());
    const core::Diagnostic& d = r.diagnostics.back();
    EXPECT_EQ(d.code, "non_manifold");
    EXPECT_NE(d.message.find("touch along an edge or at a vertex"), std::string::npos) << d.message;
    ASSERT_EQ(d.entities.size(), 1u);  // one edge (its two vertices lie on it), or one vertex
    EXPECT_EQ(d.entities[0].rfind(what, 0), 0u) << d.entities[0];
  }
}

TEST(ReadSolid, LooseFacesAreNoSolid) {
  const std::string path = temp_path("faces.brep");
  ASSERT_TRUE(detail::write_fixture(detail::Fixture::box_faces, path));
  const auto d = only_error(read_solid(path));
  EXPECT_EQ(d.code, "no_solid");
  EXPECT_NE(d.message.find("contains 3 faces and no solid"), std::string::npos);
}

TEST(ReadSolid, ClosedShellIsMadeASolid) {
  const std::string path = temp_path("closed_shell.brep");
  ASSERT_TRUE(detail::write_fixture(detail::Fixture::closed_box_shell, path));
  const ReadResult r = read_solid(path);
  ASSERT_TRUE(r.ok());
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_EQ(r.diagnostics.front().code, "closed_shell_made_solid");
  EXPECT_EQ(r.diagnostics.front().severity, core::Severity::info);
  EXPECT_NEAR(r.solid->volume(), 1.0, 1e-9);
  EXPECT_EQ(r.solid->num_faces(), 6);
}

// A solid whose vertex lies farther from its edges than its tolerance fails OCCT's check;
// the reader repairs it with ShapeFix and says so.
TEST(ReadSolid, BadTolerancesAreRepairedAndReported) {
  const std::string path = temp_path("bad_tolerance.brep");
  ASSERT_TRUE(detail::write_fixture(detail::Fixture::bad_tolerance_box, path));
  const ReadResult r = read_solid(path);
  ASSERT_TRUE(r.ok()) << (r.diagnostics.empty() ? "" : r.diagnostics.front().message);
  const core::Diagnostic* d = nullptr;
  for (const core::Diagnostic& x : r.diagnostics)
    if (x.code == "shape_repaired") d = &x;
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->severity, core::Severity::warning);
  EXPECT_NE(d->message.find("ShapeFix"), std::string::npos) << d->message;
  EXPECT_NEAR(r.solid->volume(), 1.0, 1e-3);
  EXPECT_EQ(r.solid->num_faces(), 6);
}

// A prism on a bow-tie outline: its side faces cross, OCCT's check fails and its healing
// cannot make a solid of it. Refused with a message saying so, from a file and from BREP
// text (as FreeCAD hands shapes over).
TEST(ReadSolid, SelfIntersectingSolidIsRefused) {
  const std::string path = temp_path("bowtie.brep");
  ASSERT_TRUE(detail::write_fixture(detail::Fixture::self_intersecting_prism, path));
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const ReadResult& r : {read_solid(path), read_solid_from_brep_string(text)}) {
    ASSERT_FALSE(r.ok());
    ASSERT_FALSE(r.diagnostics.empty());
    const core::Diagnostic& d = r.diagnostics.front();
    EXPECT_EQ(d.code, "invalid_shape");
    EXPECT_NE(d.message.find("self-intersecting"), std::string::npos) << d.message;
    EXPECT_NE(d.message.find("could not repair it"), std::string::npos) << d.message;
  }
}

TEST(ReadSolid, BoxRoundTripsThroughStepAndBrep) {
  const Solid box = make_box(1, 2, 3);
  for (const std::string name : {"box.step", "box.stp", "box.brep"}) {
    const std::string path = temp_path(name);
    std::string error;
    ASSERT_TRUE(write_solid(box, path, &error)) << error;
    const ReadResult r = read_solid(path);
    ASSERT_TRUE(r.ok()) << (r.diagnostics.empty() ? "" : format(r.diagnostics[0]));
    EXPECT_FALSE(core::has_error(r.diagnostics));
    EXPECT_NEAR(r.solid->volume(), 6.0, 1e-9) << name;
    EXPECT_EQ(r.solid->num_faces(), 6) << name;
    EXPECT_EQ(r.solid->num_edges(), 12) << name;
  }
}

TEST(ReadSolid, WriteRefusesUnknownExtension) {
  std::string error;
  EXPECT_FALSE(write_solid(make_box(1, 1, 1), temp_path("box.obj"), &error));
  EXPECT_NE(error.find(".step"), std::string::npos);
}

TEST(ReadSolidFromBrepString, RoundTripKeepsTopologyAndVolume) {
  const Solid brick = make_tapered_brick(3, 2, 1, 0.5);
  const ReadResult r = read_solid_from_brep_string(brick.to_brep_string());
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.solid->volume(), brick.volume(), 1e-12);
  EXPECT_EQ(r.solid->num_faces(), 6);
  EXPECT_EQ(r.solid->num_vertices(), 8);
  // Same ids: Face k has the same area after the round trip.
  for (FaceId f : brick.faces()) EXPECT_NEAR(r.solid->area(f), brick.area(f), 1e-12);
}

TEST(ReadSolidFromBrepString, GarbageAndEmptyStringsFailCleanly) {
  EXPECT_EQ(only_error(read_solid_from_brep_string("")).code, "empty_file");
  const auto d = only_error(read_solid_from_brep_string("hello world"));
  EXPECT_EQ(d.code, "unreadable_file");
  EXPECT_NE(d.message.find("BREP string"), std::string::npos);
  // A truncated valid string must not crash either.
  const std::string s = make_box(1, 1, 1).to_brep_string();
  const ReadResult r = read_solid_from_brep_string(s.substr(0, s.size() / 2));
  EXPECT_FALSE(r.ok());
}

// Every HexMe model the tests carry (tests/data/hexme, listed in its INDEX.md) reads as one
// valid solid with positive volume. The whole benchmark of 57 is read by bench/run_hexme.py.
TEST(ReadSolid, HexMeModelsReadAsSolids) {
  std::ifstream index(std::string(VOROHEX_HEXME_DIR) + "/INDEX.md");
  ASSERT_TRUE(index) << "INDEX.md missing in " << VOROHEX_HEXME_DIR;
  int listed = 0;
  for (std::string line; std::getline(index, line);)
    if (line.rfind("| ", 0) == 0 && line.find("model") == std::string::npos) ++listed;
  int models = 0;
  for (const auto& entry : std::filesystem::directory_iterator(VOROHEX_HEXME_DIR)) {
    if (entry.path().extension() != ".step") continue;
    ++models;
    const ReadResult r = read_solid(entry.path().string());
    ASSERT_TRUE(r.ok()) << entry.path() << ": "
                        << (r.diagnostics.empty() ? "" : format(r.diagnostics[0]));
    EXPECT_GT(r.solid->volume(), 0) << entry.path();
    EXPECT_GE(r.solid->num_faces(), 1) << entry.path();
  }
  EXPECT_GE(models, 10);
  EXPECT_EQ(models, listed);
}

// A fixture written to a temporary file and read back (the file removed again).
ReadResult read_fixture(detail::Fixture kind, const std::string& file) {
  const std::string path = ::testing::TempDir() + "/" + file;
  if (!detail::write_fixture(kind, path)) return {};
  ReadResult r = read_solid(path);
  std::remove(path.c_str());
  return r;
}

}  // namespace

// Turned faces stored as surfaces of revolution of a line get the cylinder or cone they are
// when read (elementary_surfaces), with the same points: the volume, each face's area and
// the order of the faces stay; the cylinder is then one the cuts at concave edges can follow.
TEST(ReadSolid, SurfacesOfRevolutionOfALineAreReadAsCylindersAndCones) {
  struct Case {
    detail::Fixture kind;
    const char* file;
    double volume, lateral_area;
  };
  const double slant = std::sqrt(4.0 + 16.0);
  for (const Case& c : {Case{detail::Fixture::revolved_cylinder, "revolved_cylinder.brep",
                             M_PI * 4 * 5, 2 * M_PI * 2 * 5},
                        Case{detail::Fixture::revolved_cone, "revolved_cone.brep",
                             M_PI * 4 / 3 * (9 + 3 + 1), M_PI * (3 + 1) * slant}}) {
    SCOPED_TRACE(c.file);
    const ReadResult r = read_fixture(c.kind, c.file);
    ASSERT_TRUE(r.ok());
    const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "elementary_surfaces");
    ASSERT_NE(d, nullptr);
    EXPECT_NE(d->message.find("1 face "), std::string::npos) << d->message;
    EXPECT_NEAR(r.solid->volume(), c.volume, 1e-9 * c.volume);
    ASSERT_EQ(r.solid->num_faces(), 3);
    // Face1 is the lateral face (OCCT's primitives and ConvertToRevolution keep the order).
    EXPECT_NEAR(r.solid->area(core::FaceId(1)), c.lateral_area, 1e-6 * c.lateral_area);
    CutCylinder cyl;
    EXPECT_EQ(face_cylinder(*r.solid, core::FaceId(1), &cyl),
              c.kind == detail::Fixture::revolved_cylinder);
    if (c.kind == detail::Fixture::revolved_cylinder) {
      EXPECT_NEAR(cyl.radius, 2, 1e-12);
      EXPECT_NEAR(std::abs(cyl.axis.z()), 1, 1e-12);
    }
    EXPECT_EQ(r.solid->surface_info(core::FaceId(1)).kind,
              c.kind == detail::Fixture::revolved_cylinder ? core::SurfaceKind::cylinder
                                                           : core::SurfaceKind::cone);
  }
}

// Faces stored as B-spline surfaces that are cylinders and planes get those when read
// (canonical_surfaces): every face of the half cylinder is a B-spline (NurbsConvert); the
// round one becomes a cylinder of radius 2 about z, the four flat ones planes, and the
// volume stays.
TEST(ReadSolid, BSplineCylindersAndPlanesAreReadAsCylindersAndPlanes) {
  const ReadResult r = read_fixture(detail::Fixture::bspline_half_cylinder, "half_cylinder.brep");
  ASSERT_TRUE(r.ok());
  const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "canonical_surfaces");
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find("5 faces as B-spline surfaces"), std::string::npos) << d->message;
  EXPECT_NE(d->message.find("1 cylinder and 4 planes"), std::string::npos) << d->message;
  EXPECT_NEAR(r.solid->volume(), M_PI * 4 * 5 / 2, 1e-9 * M_PI * 10);
  int cylinders = 0, planes = 0;
  for (int f = 1; f <= r.solid->num_faces(); ++f) {
    planes += r.solid->surface_info(core::FaceId(f)).kind == core::SurfaceKind::plane ? 1 : 0;
    CutCylinder cyl;
    if (!face_cylinder(*r.solid, core::FaceId(f), &cyl)) continue;
    ++cylinders;
    EXPECT_NEAR(cyl.radius, 2, 1e-9);
    EXPECT_NEAR(std::abs(cyl.axis.z()), 1, 1e-9);
    EXPECT_NEAR(r.solid->area(core::FaceId(f)), M_PI * 2 * 5, 1e-6 * M_PI * 10);
  }
  EXPECT_EQ(cylinders, 1);
  EXPECT_EQ(planes, 4);
}

// The same for closed faces: a NURBS tube's two round faces (each bounding its seam edge
// twice) become cylinders of radii 1 and 2 with their seams where they were, and the tube
// stays valid with its volume.
TEST(ReadSolid, ClosedBSplineCylindersAreReadAsCylinders) {
  const ReadResult r = read_fixture(detail::Fixture::bspline_tube, "bspline_tube.brep");
  ASSERT_TRUE(r.ok());
  const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "canonical_surfaces");
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find("2 cylinders and 2 planes"), std::string::npos) << d->message;
  EXPECT_NEAR(r.solid->volume(), M_PI * 3 * 5, 1e-9 * M_PI * 15);
  std::vector<double> radii;
  for (int f = 1; f <= r.solid->num_faces(); ++f) {
    CutCylinder cyl;
    if (face_cylinder(*r.solid, core::FaceId(f), &cyl)) radii.push_back(cyl.radius);
  }
  std::sort(radii.begin(), radii.end());
  ASSERT_EQ(radii.size(), 2u);
  EXPECT_NEAR(radii[0], 1, 1e-9);
  EXPECT_NEAR(radii[1], 2, 1e-9);
}

// HexMe i12's boss is a cylinder on one side and a B-spline 5e-5 off that cylinder on the
// other; read, the B-spline gets that very cylinder (so the cut along it and the unification
// of the boss's faces see one surface), and the solid stays valid with its 45 faces.
TEST(ReadSolid, AHalfBossStoredAsABSplineGetsTheOtherHalfsCylinder) {
  const ReadResult r = read_solid(std::string(VOROHEX_HEXME_DIR) + "/i12o_s5.step");
  ASSERT_TRUE(r.ok());
  const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "canonical_surfaces");
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find("1 face "), std::string::npos) << d->message;
  EXPECT_NE(d->message.find("1 cylinder (on the cylinder of another of its faces)"),
            std::string::npos)
      << d->message;
  EXPECT_EQ(r.solid->num_faces(), 45);
  // Face5, the B-spline, on the boss's cylinder: radius 14 about the z axis through
  // (-53, 45), as Face9 (the analytic half) is.
  for (int f : {5, 9}) {
    CutCylinder cyl;
    ASSERT_TRUE(face_cylinder(*r.solid, core::FaceId(f), &cyl)) << "Face" << f;
    EXPECT_NEAR(cyl.radius, 14, 1e-9);
    EXPECT_NEAR(std::abs(cyl.axis.z()), 1, 1e-12);
    EXPECT_NEAR(cyl.origin.x(), -53, 1e-6);
    EXPECT_NEAR(cyl.origin.y(), 45, 1e-6);
  }
}

}  // namespace vorohex::occ
