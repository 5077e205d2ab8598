#include "occ/detail/elementary_surfaces.h"

#include <BRepTools.hxx>
#include <BRepTools_Modifier.hxx>
#include <BRep_Tool.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_Surface.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Ax3.hxx>
#include <gp_Lin.hxx>

#include <cmath>
#include <map>

#include "occ/detail/surface_swap.h"

namespace vorohex::occ::detail {
namespace {

// The cylinder or cone with the parametrisation of `rev` (u: the angle about the axis, v:
// the meridian line's parameter), or null when the meridian is no line in a plane through
// the axis. Geom_SurfaceOfRevolution turns C(v) by u anticlockwise about its axis direction
// A; the elementary surfaces give O + r(v) (cos u X + sin u Y) + h(v) Z, so X points from
// the axis to the line, Y = A x X (an indirect frame where Z = -A).
Handle(Geom_Surface) same_surface(const Handle(Geom_SurfaceOfRevolution) & rev) {
  const GeomAdaptor_Surface s(rev);
  const Handle(Adaptor3d_Curve) meridian = s.BasisCurve();
  if (meridian.IsNull() || meridian->GetType() != GeomAbs_Line) return nullptr;
  const gp_Ax1 axis = rev->Axis();
  const gp_Vec a(axis.Direction());
  const gp_Lin line = meridian->Line();
  const gp_Vec d(line.Direction());
  // The meridian's parameter is the line's (a trimmed line keeps its basis parameter).
  const gp_Pnt l0 = line.Location();
  const gp_Vec from_axis(axis.Location(), l0);
  const gp_Pnt foot = axis.Location().Translated(from_axis.Dot(a) * a);
  gp_Vec radial(foot, l0);
  const double r = radial.Magnitude();
  const double sa = d.Dot(a);
  const gp_Vec db = d - sa * a;  // the line's radial component
  // In a plane through the axis: the radial parts of l0 and d are parallel.
  if (r > 1e-12 && db.Magnitude() > 1e-12 &&
      radial.Crossed(db).Magnitude() > 1e-9 * r * db.Magnitude())
    return nullptr;
  if (r <= 1e-12) {  // l0 on the axis: the radial direction from the line's slope
    if (db.Magnitude() <= 1e-12) return nullptr;
    radial = db;
  }
  const gp_Dir x(radial);
  const gp_Dir z(sa >= 0 ? a : -a);
  gp_Ax3 frame(foot, z, x);
  if (sa < 0) frame.YReverse();       // Y = A x X
  const double b = d.Dot(gp_Vec(x));  // the radius grows by b per unit of v
  if (std::abs(b) <= 1e-12) return new Geom_CylindricalSurface(frame, r);
  if (std::abs(sa) <= 1e-9) return nullptr;  // a plane (or a ring): not by angle and radius
  const double angle = std::atan2(b, std::abs(sa));
  if (std::abs(angle) >= M_PI / 2 - 1e-9) return nullptr;
  return new Geom_ConicalSurface(frame, angle, r);
}

// Same parametrisation: the curves on the faces are the old ones.
class ToElementary : public SurfaceSwap {
 public:
  explicit ToElementary(std::map<const void*, Handle(Geom_Surface)> by_face)
      : SurfaceSwap(std::move(by_face), true) {}

  Standard_Boolean NewCurve2d(const TopoDS_Edge& e, const TopoDS_Face& f, const TopoDS_Edge&,
                              const TopoDS_Face&, Handle(Geom2d_Curve) & c,
                              Standard_Real& tol) override {
    if (!surface_of(f)) return false;
    double first, last;
    c = BRep_Tool::CurveOnSurface(e, f, first, last);
    tol = BRep_Tool::Tolerance(e);
    return !c.IsNull();
  }
};

}  // namespace

ElementaryResult elementary_surfaces(const TopoDS_Solid& solid) {
  ElementaryResult out;
  try {
    std::map<const void*, Handle(Geom_Surface)> by_face;
    for (TopExp_Explorer ex(solid, TopAbs_FACE); ex.More(); ex.Next()) {
      const TopoDS_Face& f = TopoDS::Face(ex.Current());
      TopLoc_Location l;
      Handle(Geom_Surface) s = BRep_Tool::Surface(f, l);
      if (s.IsNull()) continue;
      if (auto t = Handle(Geom_RectangularTrimmedSurface)::DownCast(s)) s = t->BasisSurface();
      const auto rev = Handle(Geom_SurfaceOfRevolution)::DownCast(s);
      if (rev.IsNull() || by_face.count(f.TShape().get())) continue;
      const Handle(Geom_Surface) e = same_surface(rev);
      if (e.IsNull()) continue;
      // The same points over the face's parameter range (a 9 x 9 sample).
      double u0, u1, v0, v1;
      BRepTools::UVBounds(f, u0, u1, v0, v1);
      const double scale = std::max(1.0, rev->Value(u0, v0).Distance(rev->Value(u1, v1)));
      bool same = true;
      for (int i = 0; i <= 8 && same; ++i)
        for (int j = 0; j <= 8 && same; ++j) {
          const double u = u0 + (u1 - u0) * i / 8, v = v0 + (v1 - v0) * j / 8;
          same = rev->Value(u, v).Distance(e->Value(u, v)) <= 1e-9 * scale;
        }
      if (same) by_face[f.TShape().get()] = e;
    }
    if (by_face.empty()) return out;
    Handle(ToElementary) modification = new ToElementary(by_face);
    BRepTools_Modifier modifier(solid, modification);
    if (!modifier.IsDone()) return out;
    const TopoDS_Shape result = modifier.ModifiedShape(solid);
    if (result.IsNull() || result.ShapeType() != TopAbs_SOLID) return out;
    out.solid = TopoDS::Solid(result);
    out.converted = int(by_face.size());
  } catch (const Standard_Failure&) {
    out = ElementaryResult();
  }
  return out;
}

}  // namespace vorohex::occ::detail
