#include "occ/detail/face_classifier.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace vorohex::occ::detail
