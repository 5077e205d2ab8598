#include "occ/face_chart.h"

#include <gtest/gtest.h>
#include <BRepAlgoAPI_Common.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Ax2.hxx>

#include <cmath>

#include "occ/solid_impl.h"

namespace vorohex::occ {
namespace {

using core::FaceId;
using core::Vec3;

// The lower half of a cylinder of radius 2 about the z axis, cut out of the whole one: its
// curved face keeps the whole cylinder's parametrisation, u in [pi, 2 pi].
Solid lower_half_cylinder() {
  const TopoDS_Shape cylinder =
      BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 2, 3).Shape();
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(-5, -5, -1), gp_Pnt(5, 0, 4)).Shape();
  TopExp_Explorer solids(BRepAlgoAPI_Common(cylinder, box).Shape(), TopAbs_SOLID);
  return make_solid(TopoDS::Solid(solids.Current()));
}

// A point on the half's edge at u = 2 pi is found at u = 0 by OCCT, a whole period away from
// the rest of the face in the chart (a pillow block's half ring over its bore, swept from its
// outer cylinder: its source's boundary loops crossed in the chart, and the quad mesher
// failed). The chart takes the period nearest the face's middle.
TEST(FaceChart, APeriodicFacesChartIsOnePieceWhereItsRangeIsNotThePeriods) {
  const Solid half = lower_half_cylinder();
  FaceId curved;
  for (FaceId f : half.faces())
    if (!half.face_is_planar(f)) curved = f;
  ASSERT_TRUE(curved.valid());
  ASSERT_NEAR(half.impl().face(curved.value()).umin, M_PI, 1e-9);
  ASSERT_NEAR(half.impl().face(curved.value()).umax, 2 * M_PI, 1e-9);
  const FaceChart chart(half, curved);
  // Along the face at one height: the chart's first coordinate grows with the angle, from
  // the edge at u = pi to the edge at u = 2 pi, and maps back onto the same points.
  double last = -1e300;
  for (int k = 0; k <= 8; ++k) {
    // The last on the edge, rounded to its far side (as a node placed there may be).
    const double a = M_PI + M_PI * k / 8 + (k == 8 ? 1e-12 : 0);
    const Vec3 p(2 * std::cos(a), 2 * std::sin(a), 1.5);
    const Eigen::Vector2d q = chart.to_chart(p);
    EXPECT_GT(q.x(), last) << k;
    last = q.x();
    EXPECT_LT((chart.to_surface(q) - p).norm(), 1e-9) << k;
  }
  // Its ends a half turn apart: the half circumference, with the chart's scale of 2.
  EXPECT_NEAR(last - chart.to_chart(Vec3(-2, 0, 1.5)).x(), 2 * M_PI, 1e-9);
}

}  // namespace
}  // namespace vorohex::occ
