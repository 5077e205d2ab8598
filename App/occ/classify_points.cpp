#include "occ/classify_points.h"

#include <BRepClass3d_SolidClassifier.hxx>
#include <Standard_Failure.hxx>

#include "occ/solid_impl.h"

namespace vorohex::occ {

std::vector<PointState> classify_points(const Solid& solid, const std::vector<Vec3>& points,
                                        double tolerance) {
  std::vector<PointState> out(points.size(), PointState::on);
  if (points.empty()) return out;
  try {
    BRepClass3d_SolidClassifier classifier(solid.impl().solid);
    for (std::size_t i = 0; i < points.size(); ++i) {
      try {
        classifier.Perform(gp_Pnt(points[i].x(), points[i].y(), points[i].z()), tolerance);
        const TopAbs_State s = classifier.State();
        out[i] = s == TopAbs_IN    ? PointState::inside
                 : s == TopAbs_OUT ? PointState::outside
                                   : PointState::on;
      } catch (const Standard_Failure&) {
        out[i] = PointState::on;
      }
    }
  } catch (const Standard_Failure&) {
  }
  return out;
}

}  // namespace vorohex::occ
