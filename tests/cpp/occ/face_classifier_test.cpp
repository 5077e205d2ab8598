#include "occ/detail/face_classifier.h"

#include <gtest/gtest.h>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Pnt2d.hxx>

#include <random>
#include <string>

#include "occ/primitives.h"
#include "occ/shape_io.h"
#include "occ/solid_impl.h"

namespace vorohex::occ::detail {
namespace {

struct Agreement {
  long points = 0, differ = 0;
  int faces = 0, rastered = 0;
  double known = 0;  // mean share of raster cells answered without OCCT
};

// Every face of the solid: the raster's answers against OCCT's own classifier at random points
// of the face's parameter box and a margin around it (outside points too), and near its
// boundary (within four raster cells of the edges' pcurves, where a raster that missed the
// boundary would answer wrongly), both with and without the periodic shift.
Agreement compare(const Solid& solid, int points_per_face) {
  Agreement a;
  std::mt19937 random(7);
  for (int f = 1; f <= solid.num_faces(); ++f) {
    const TopoDS_Face face = TopoDS::Face(solid.impl().faces(f));
    const double tolerance = std::max(BRep_Tool::Tolerance(face), 1e-9);
    const FaceClassifier fast(face, tolerance, 256);
    const BRepTopAdaptor_FClass2d occt(TopoDS::Face(face.Oriented(TopAbs_FORWARD)), tolerance);
    double u0, u1, v0, v1;
    BRepTools::UVBounds(face, u0, u1, v0, v1);
    std::uniform_real_distribution<double> u(u0 - 0.1 * (u1 - u0), u1 + 0.1 * (u1 - u0));
    std::uniform_real_distribution<double> v(v0 - 0.1 * (v1 - v0), v1 + 0.1 * (v1 - v0));
    auto check = [&](double pu, double pv) {
      for (bool recadre : {false, true}) {
        ++a.points;
        a.differ += fast.perform(pu, pv, recadre) != occt.Perform(gp_Pnt2d(pu, pv), recadre);
      }
    };
    for (int k = 0; k < points_per_face; ++k) check(u(random), v(random));
    const double cell_u = (u1 - u0) / 256, cell_v = (v1 - v0) / 256;
    std::uniform_real_distribution<double> unit(0, 1), offset(-4, 4);
    for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
      double first, last;
      const Handle(Geom2d_Curve) c =
          BRep_Tool::CurveOnSurface(TopoDS::Edge(ex.Current()), face, first, last);
      if (c.IsNull()) continue;
      for (int k = 0; k < points_per_face / 10; ++k) {
        const gp_Pnt2d p = c->Value(first + (last - first) * unit(random));
        check(p.X() + offset(random) * cell_u, p.Y() + offset(random) * cell_v);
      }
    }
    ++a.faces;
    a.rastered += fast.rastered();
    a.known += fast.share_known();
  }
  a.known /= std::max(a.faces, 1);
  return a;
}

TEST(FaceClassifier, AgreesWithOcctOnPlanesCylindersAndCones) {
  for (const Solid& s : {make_cylinder(2, 5), make_cone(3, 1, 4, Vec3(0, 0, 0), Vec3(1, 1, 0)),
                         make_torus(5, 1, Vec3(0, 0, 0), Vec3(0, 0, 1)),
                         make_prism({{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 3}, {0, 3}}, 2)}) {
    const Agreement a = compare(s, 4000);
    EXPECT_EQ(a.differ, 0) << "of " << a.points;
    EXPECT_EQ(a.rastered, a.faces);
    EXPECT_GT(a.known, 0.8);  // most of the box is answered without OCCT
  }
}

// Real parts: B-spline faces, faces with holes, trimmed periodic faces (HexMe i02: a hole at
// 45 degrees and a countersink; i09: many small features).
TEST(FaceClassifier, AgreesWithOcctOnHexMeParts) {
  for (const char* model : {"i02o_m2.step", "i09o_m9.step", "s05o_cube_sphere.step"}) {
    const ReadResult in = read_solid(std::string(VOROHEX_HEXME_DIR) + "/" + model);
    ASSERT_TRUE(in.ok()) << model;
    const Agreement a = compare(*in.solid, 2000);
    EXPECT_EQ(a.differ, 0) << model << ": of " << a.points;
    EXPECT_GT(a.rastered, a.faces * 9 / 10) << model;
    EXPECT_GT(a.known, 0.5) << model;
  }
}

// Edges on a plane often carry no pcurve (a face made from a 3D polygon, STEP, OCCT's
// booleans): OCCT projects each 3D curve onto the plane whenever one is asked for. The
// classifier answers from its own copy of the face with the pcurves stored - the same
// answers as OCCT's on the face as it is - and leaves the caller's face without them.
TEST(FaceClassifier, APlaneWithoutStoredPcurvesAnswersAsOcctAndIsLeftAsItWas) {
  BRepBuilderAPI_MakePolygon polygon;
  for (const auto& [x, y] :
       std::vector<std::pair<double, double>>{{0, 0}, {4, 0}, {4, 1}, {1.5, 1.2}, {1, 3}, {0, 3}})
    polygon.Add(gp_Pnt(x, y, 0.5 * x));
  polygon.Close();
  const TopoDS_Face face = BRepBuilderAPI_MakeFace(polygon.Wire(), /*OnlyPlane=*/true).Face();
  auto stored_pcurves = [&] {
    int stored = 0;
    for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
      Standard_Boolean is_stored = Standard_False;
      double first, last;
      BRep_Tool::CurveOnSurface(TopoDS::Edge(ex.Current()), face, first, last, &is_stored);
      stored += is_stored ? 1 : 0;
    }
    return stored;
  };
  ASSERT_EQ(stored_pcurves(), 0);  // the case itself: OCCT would project on every call

  const double tolerance = std::max(BRep_Tool::Tolerance(face), 1e-9);
  const FaceClassifier fast(face, tolerance, 256);
  const BRepTopAdaptor_FClass2d occt(face, tolerance);
  EXPECT_EQ(stored_pcurves(), 0);  // the caller's face is left as it was
  double u0, u1, v0, v1;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0, 1), offset(-1, 1);
  long points = 0, differ = 0, on = 0;
  for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
    double first, last;
    const Handle(Geom2d_Curve) c =
        BRep_Tool::CurveOnSurface(TopoDS::Edge(ex.Current()), face, first, last);
    ASSERT_FALSE(c.IsNull());
    // On the boundary and just off it (OCCT's exact classifier answers these), 600 times:
    // past the questions after which the raster is built, so both paths are compared.
    for (int k = 0; k < 100; ++k) {
      const gp_Pnt2d p = c->Value(first + (last - first) * unit(random));
      // Half within OCCT's tolerance of the boundary (ON), half up to 1e-4 of the box away.
      const double away = k % 2 ? 0.5 * tolerance : 1e-4 * std::max(u1 - u0, v1 - v0);
      const gp_Pnt2d q(p.X() + offset(random) * away, p.Y() + offset(random) * away);
      const TopAbs_State expected = occt.Perform(q, false);
      ++points;
      on += expected == TopAbs_ON;
      differ += fast.perform(q.X(), q.Y(), false) != expected;
    }
  }
  EXPECT_EQ(differ, 0) << "of " << points;
  EXPECT_GT(on, points / 4);  // the ones within the tolerance on the boundary, as meant
  EXPECT_TRUE(fast.rastered());
}

}  // namespace
}  // namespace vorohex::occ::detail
