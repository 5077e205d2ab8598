#include "occ/detail/canonical_surfaces.h"

#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <BRepLib.hxx>
#include <BRepTools.hxx>
#include <BRepTools_Modifier.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <ElSLib.hxx>
#include <GProp_GProps.hxx>
#include <Geom2d_Curve.hxx>
#include <GeomLib_IsPlanarSurface.hxx>
#include <GeomProjLib.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_Curve.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_Plane.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_Surface.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Ax3.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Pln.hxx>
#include <gp_Vec2d.hxx>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <vector>

#include "occ/detail/surface_swap.h"

namespace vorohex::occ::detail {
namespace {

// The surface under a face (located: in global coordinates), without its trimming.
Handle(Geom_Surface) basis_of(const TopoDS_Face& f) {
  Handle(Geom_Surface) s = BRep_Tool::Surface(f);
  if (auto t = Handle(Geom_RectangularTrimmedSurface)::DownCast(s)) s = t->BasisSurface();
  return s;
}

bool is_bspline(const Handle(Geom_Surface) & b) {
  return !Handle(Geom_BSplineSurface)::DownCast(b).IsNull() ||
         !Handle(Geom_BezierSurface)::DownCast(b).IsNull();
}

struct Sample {
  Eigen::Vector3d point, normal;  // the natural normal of the surface (not the face's)
};

// An 11 x 11 sample of the face's surface over its parameter range (global coordinates).
std::vector<Sample> samples_of(const TopoDS_Face& f) {
  std::vector<Sample> out;
  const Handle(Geom_Surface) s = BRep_Tool::Surface(f);  // located
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  const int n = 10;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      gp_Pnt p;
      gp_Vec du, dv;
      s->D1(u0 + (u1 - u0) * i / n, v0 + (v1 - v0) * j / n, p, du, dv);
      const gp_Vec nv = du.Crossed(dv);
      if (nv.Magnitude() < 1e-12) continue;
      const gp_Vec un = nv.Normalized();
      out.push_back({{p.X(), p.Y(), p.Z()}, {un.X(), un.Y(), un.Z()}});
    }
  return out;
}

struct Fit {
  Eigen::Vector3d origin, axis;
  double radius = 0;
  double deviation = 0;         // the largest |distance to the axis - radius| over the samples
  std::optional<gp_Ax3> frame;  // an analytic cylinder's own frame (its seam), if any
};

double deviation_of(const std::vector<Sample>& samples, const Eigen::Vector3d& o,
                    const Eigen::Vector3d& a, double r) {
  double worst = 0;
  for (const Sample& s : samples) {
    const Eigen::Vector3d d = s.point - o;
    worst = std::max(worst, std::abs((d - d.dot(a) * a).norm() - r));
  }
  return worst;
}

// The cylinder through the samples: the axis first from the normals (the direction they are
// all perpendicular to), the circle fitted across it (Kasa's algebraic fit), then the five
// parameters refined by Gauss-Newton on the distances. False where the normals are not all
// perpendicular to one direction (to 1e-2): no cylinder.
bool fit_cylinder(const std::vector<Sample>& samples, Fit& fit) {
  if (samples.size() < 12) return false;
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (const Sample& s : samples) m += s.normal * s.normal.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(m);
  Eigen::Vector3d a = eig.eigenvectors().col(0).normalized();
  for (const Sample& s : samples)
    if (std::abs(s.normal.dot(a)) > 1e-2) return false;
  // A frame across the axis, and Kasa's fit of x^2 + y^2 + D x + E y + F = 0.
  Eigen::Vector3d e1 = a.unitOrthogonal(), e2 = a.cross(e1);
  Eigen::MatrixXd lhs(samples.size(), 3);
  Eigen::VectorXd rhs(samples.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const double x = samples[k].point.dot(e1), y = samples[k].point.dot(e2);
    lhs.row(Eigen::Index(k)) << x, y, 1;
    rhs(Eigen::Index(k)) = -(x * x + y * y);
  }
  const Eigen::Vector3d def = lhs.colPivHouseholderQr().solve(rhs);
  const double cx = -def(0) / 2, cy = -def(1) / 2, r2 = cx * cx + cy * cy - def(2);
  if (!(r2 > 0)) return false;
  Eigen::Vector3d o = cx * e1 + cy * e2;
  double r = std::sqrt(r2);
  // Gauss-Newton on (shift of the axis across itself: 2, tilt: 2, radius: 1).
  for (int it = 0; it < 8; ++it) {
    e1 = a.unitOrthogonal(), e2 = a.cross(e1);
    auto residuals = [&](const Eigen::Matrix<double, 5, 1>& p) {
      const Eigen::Vector3d oo = o + p(0) * e1 + p(1) * e2;
      const Eigen::Vector3d aa = (a + p(2) * e1 + p(3) * e2).normalized();
      Eigen::VectorXd res(samples.size());
      for (std::size_t k = 0; k < samples.size(); ++k) {
        const Eigen::Vector3d d = samples[k].point - oo;
        res(Eigen::Index(k)) = (d - d.dot(aa) * aa).norm() - (r + p(4));
      }
      return res;
    };
    const Eigen::Matrix<double, 5, 1> zero = Eigen::Matrix<double, 5, 1>::Zero();
    const Eigen::VectorXd r0 = residuals(zero);
    Eigen::MatrixXd jac(samples.size(), 5);
    for (int c = 0; c < 5; ++c) {
      Eigen::Matrix<double, 5, 1> p = zero;
      const double h = c < 2 || c == 4 ? 1e-6 * std::max(1.0, r) : 1e-7;
      p(c) = h;
      jac.col(c) = (residuals(p) - r0) / h;
    }
    const Eigen::Matrix<double, 5, 1> step = jac.colPivHouseholderQr().solve(-r0);
    o += step(0) * e1 + step(1) * e2;
    a = (a + step(2) * e1 + step(3) * e2).normalized();
    r += step(4);
    if (step.norm() < 1e-12 * std::max(1.0, r)) break;
  }
  // The axis point nearest the samples' centre, so that it stays in range.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Sample& s : samples) centre += s.point;
  centre /= double(samples.size());
  o += (centre - o).dot(a) * a;
  fit = {o, a, r, deviation_of(samples, o, a, r), std::nullopt};
  return r > 0;
}

// The analytic cylinders of the solid's own faces (global axis, radius and frame).
std::vector<Fit> cylinders_of(const TopoDS_Solid& solid) {
  std::vector<Fit> out;
  for (TopExp_Explorer ex(solid, TopAbs_FACE); ex.More(); ex.Next()) {
    const auto c = Handle(Geom_CylindricalSurface)::DownCast(basis_of(TopoDS::Face(ex.Current())));
    if (c.IsNull()) continue;
    const gp_Ax3 frame = c->Position();
    const gp_Pnt o = frame.Location();
    const gp_Dir d = frame.Direction();
    out.push_back({{o.X(), o.Y(), o.Z()}, {d.X(), d.Y(), d.Z()}, c->Radius(), 0, frame});
  }
  return out;
}

// A cylinder for the face and where its parameter range starts (`seam`: the face lies in
// u in [seam, seam + 2 pi)). Its frame is an analytic cylinder's where the fit was snapped
// to one (the same seam, so that OCCT unifies the two faces as one surface), else one with
// its seam in the middle of the widest gap of the samples' angles; direct or not so that its
// normal is the B-spline's (the face keeps its orientation and wires). A closed face (one
// with a seam edge: `seam_point` on it) gets its seam there; null where the samples of a
// face without one go round with no gap of 10 degrees.
Handle(Geom_CylindricalSurface) cylinder_for(const std::vector<Sample>& samples, const Fit& fit,
                                             const gp_Pnt* seam_point, double& seam) {
  const Eigen::Vector3d a = fit.axis;
  gp_Ax3 frame;
  if (fit.frame) {
    frame = *fit.frame;
  } else {
    const Eigen::Vector3d e1 = a.unitOrthogonal();
    frame = gp_Ax3(gp_Pnt(fit.origin.x(), fit.origin.y(), fit.origin.z()),
                   gp_Dir(a.x(), a.y(), a.z()), gp_Dir(e1.x(), e1.y(), e1.z()));
  }
  // Outward (from the axis) or inward, as the B-spline's normal at its first sample.
  const Eigen::Vector3d d0 = samples.front().point - fit.origin;
  const bool outward = samples.front().normal.dot(d0 - d0.dot(a) * a) > 0;
  if (frame.Direct() != outward) frame.YReverse();
  Handle(Geom_CylindricalSurface) cyl = new Geom_CylindricalSurface(frame, fit.radius);
  const gp_Cylinder c = cyl->Cylinder();
  std::vector<double> angles;
  for (const Sample& s : samples) {
    double u, v;
    ElSLib::Parameters(c, gp_Pnt(s.point.x(), s.point.y(), s.point.z()), u, v);
    angles.push_back(u);
  }
  std::sort(angles.begin(), angles.end());
  double gap = angles.front() + 2 * M_PI - angles.back(), middle = angles.back() + gap / 2;
  for (std::size_t k = 1; k < angles.size(); ++k)
    if (angles[k] - angles[k - 1] > gap)
      gap = angles[k] - angles[k - 1], middle = (angles[k] + angles[k - 1]) / 2;
  if (seam_point) {  // a closed face: its seam where its seam edge is
    double v;
    ElSLib::Parameters(c, *seam_point, middle, v);
  } else if (gap < 10 * M_PI / 180) {
    return nullptr;
  }
  seam = middle - 2 * M_PI * std::floor(middle / (2 * M_PI));
  if (!fit.frame) {  // turn the frame so that the seam is at u = 0
    frame.Rotate(frame.Axis(), frame.Direct() ? seam : -seam);
    cyl = new Geom_CylindricalSurface(frame, fit.radius);
    seam = 0;
  }
  return cyl;
}

// The cylinders and planes by face (global), and where each cylinder's turn starts (its
// faces lie in u in [seam, seam + 2 pi)).
class ToCylinders : public SurfaceSwap {
 public:
  ToCylinders(std::map<const void*, Handle(Geom_Surface)> by_face,
              std::map<const void*, double> seams)
      : SurfaceSwap(std::move(by_face), false), seams_(std::move(seams)) {}

  // The edge's curve projected onto the face's cylinder or plane; on a cylinder in the turn
  // the face lies in (from its seam; a seam edge at the side the face lies on), with a
  // tolerance that covers the projection.
  Standard_Boolean NewCurve2d(const TopoDS_Edge& e, const TopoDS_Face& f, const TopoDS_Edge&,
                              const TopoDS_Face&, Handle(Geom2d_Curve) & c,
                              Standard_Real& tol) override {
    const Handle(Geom_Surface)* swapped = surface_of(f);
    if (!swapped) return false;
    const Handle(Geom_Surface)& surface = *swapped;
    const double seam = seams_.count(f.TShape().get()) ? seams_.at(f.TShape().get()) : 0;
    double first, last;
    const Handle(Geom_Curve) curve = BRep_Tool::Curve(e, first, last);  // located
    if (curve.IsNull()) return false;
    double reached = BRep_Tool::Tolerance(e);
    c = GeomProjLib::Curve2d(curve, first, last, surface, reached);
    if (c.IsNull()) return false;
    const double mid = 0.5 * (first + last);
    const auto cylinder = Handle(Geom_CylindricalSurface)::DownCast(surface);
    const double u = c->Value(mid).X() - seam;
    double shift = cylinder.IsNull() ? 0 : -2 * M_PI * std::floor(u / (2 * M_PI));
    if (!cylinder.IsNull() && BRep_Tool::IsClosed(e, f)) {
      // The seam edge: at the start of the turn where the face lies on its left going along
      // it (+u from there), else at its end.
      gp_Pnt p;
      gp_Vec t, du, dv;
      curve->D1(mid, p, t);
      if (e.Orientation() == TopAbs_REVERSED) t.Reverse();
      double pu, pv;
      ElSLib::Parameters(cylinder->Cylinder(), p, pu, pv);
      surface->D1(pu, pv, p, du, dv);
      gp_Vec n = du.Crossed(dv);
      if (f.Orientation() == TopAbs_REVERSED) n.Reverse();
      const bool start = n.Crossed(t).Dot(du) > 0;
      const double at = seam + (start ? 0 : 2 * M_PI);
      shift = 2 * M_PI * std::round((at - c->Value(mid).X()) / (2 * M_PI));
    }
    if (shift != 0) c->Translate(gp_Vec2d(shift, 0));
    // The tolerance: the largest distance between the edge and its image on the surface.
    double worst = 0;
    for (int k = 0; k <= 16; ++k) {
      const double t = first + (last - first) * k / 16;
      const gp_Pnt2d uv = c->Value(t);
      worst = std::max(worst, curve->Value(t).Distance(surface->Value(uv.X(), uv.Y())));
    }
    tol = std::max({BRep_Tool::Tolerance(e), reached, 1.5 * worst});
    return true;
  }

 private:
  std::map<const void*, double> seams_;
};

}  // namespace

CanonicalResult canonical_surfaces(const TopoDS_Solid& solid, double relative_tolerance) {
  CanonicalResult out;
  try {
    // Nothing to do (and nothing computed) without a B-spline or Bezier face.
    bool any = false;
    for (TopExp_Explorer ex(solid, TopAbs_FACE); ex.More() && !any; ex.Next())
      any = is_bspline(basis_of(TopoDS::Face(ex.Current())));
    if (!any) return out;
    Bnd_Box box;
    BRepBndLib::Add(solid, box);
    if (box.IsVoid()) return out;
    const double size = std::sqrt(box.SquareExtent());
    const double tolerance = relative_tolerance * size;
    const std::vector<Fit> analytic = cylinders_of(solid);
    std::map<const void*, Handle(Geom_Surface)> by_face;
    std::map<const void*, double> seams;
    double deviation = 0, bound = 0;
    int snapped = 0, planes = 0;
    for (TopExp_Explorer ex(solid, TopAbs_FACE); ex.More(); ex.Next()) {
      const TopoDS_Face& f = TopoDS::Face(ex.Current());
      const Handle(Geom_Surface) b = basis_of(f);
      if (by_face.count(f.TShape().get()) || !is_bspline(b)) continue;
      const std::vector<Sample> samples = samples_of(f);
      auto area = [&] {
        GProp_GProps props;
        BRepGProp::SurfaceProperties(f, props);
        return props.Mass();
      };
      // A plane (not a cylinder of a radius large enough), its normal the B-spline's.
      if (const GeomLib_IsPlanarSurface planar(b, tolerance); planar.IsPlanar()) {
        if (samples.empty()) continue;
        gp_Pln pln = planar.Plan();
        const gp_Dir n = pln.Axis().Direction();
        const Eigen::Vector3d nn(n.X(), n.Y(), n.Z());
        if (samples.front().normal.dot(nn) < 0) pln.SetAxis(pln.Axis().Reversed());
        double dev = 0;
        for (const Sample& q : samples)
          dev = std::max(dev, pln.Distance(gp_Pnt(q.point.x(), q.point.y(), q.point.z())));
        if (!(dev <= tolerance)) continue;
        by_face[f.TShape().get()] = new Geom_Plane(pln);
        deviation = std::max(deviation, dev);
        bound += dev * area();
        ++planes;
        continue;
      }
      Fit fit;
      if (!fit_cylinder(samples, fit) || !(fit.deviation <= tolerance) || fit.radius > size)
        continue;
      // The solid's own cylinder where it is this one (within the tolerance everywhere).
      bool own = false;
      for (const Fit& c : analytic) {
        if (std::abs(c.radius - fit.radius) > tolerance) continue;
        const double dev = deviation_of(samples, c.origin, c.axis, c.radius);
        if (dev <= tolerance) {
          fit.origin = c.origin + (fit.origin - c.origin).dot(c.axis) * c.axis;
          fit.axis = c.axis;
          fit.radius = c.radius;
          fit.deviation = dev;
          fit.frame = c.frame;
          own = true;
          break;
        }
      }
      // A closed face's seam edge (bounding it twice), where its new seam goes.
      std::optional<gp_Pnt> seam_point;
      for (TopExp_Explorer ed(f, TopAbs_EDGE); ed.More() && !seam_point; ed.Next()) {
        const TopoDS_Edge& e = TopoDS::Edge(ed.Current());
        double a, z;
        const Handle(Geom_Curve) curve = BRep_Tool::Curve(e, a, z);
        if (BRep_Tool::IsClosed(e, f) && !curve.IsNull()) seam_point = curve->Value(0.5 * (a + z));
      }
      double seam = 0;
      const Handle(Geom_CylindricalSurface) cyl =
          cylinder_for(samples, fit, seam_point ? &*seam_point : nullptr, seam);
      if (cyl.IsNull()) continue;
      by_face[f.TShape().get()] = cyl;
      seams[f.TShape().get()] = seam;
      deviation = std::max(deviation, fit.deviation);
      bound += fit.deviation * area();
      snapped += own ? 1 : 0;
    }
    if (by_face.empty()) return out;
    Handle(ToCylinders) modification = new ToCylinders(by_face, seams);
    BRepTools_Modifier modifier(solid, modification);
    if (!modifier.IsDone()) return out;
    TopoDS_Shape result = modifier.ModifiedShape(solid);
    if (result.IsNull() || result.ShapeType() != TopAbs_SOLID) return out;
    BRepLib::SameParameter(result, 1e-7, Standard_True);
    BRepLib::UpdateTolerances(result, Standard_False);
    out.solid = TopoDS::Solid(result);
    out.converted = int(by_face.size()) - planes;
    out.planes = planes;
    out.snapped = snapped;
    out.deviation = deviation;
    out.volume_bound = bound;
  } catch (const Standard_Failure&) {
    out = CanonicalResult();
  }
  return out;
}

}  // namespace vorohex::occ::detail
