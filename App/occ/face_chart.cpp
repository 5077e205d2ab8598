#include "occ/face_chart.h"

#include <Eigen/Geometry>
#include <Geom_Surface.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <Standard_Failure.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

#include <cmath>
#include <stdexcept>

#include "occ/solid_impl.h"

namespace vorohex::occ {
namespace {

// x shifted by whole periods to within half a period of `middle`.
double nearest_period(double x, double middle, double period) {
  return period > 0 ? x - period * std::round((x - middle) / period) : x;
}

}  // namespace

struct FaceChart::Surface {
  Handle(Geom_Surface) surface;
  Handle(ShapeAnalysis_Surface) analysis;
};

FaceChart::FaceChart(const Solid& solid, FaceId face) {
  const FaceCache& c = solid.impl().face(face.value());
  planar_ = c.planar;
  try {
    if (planar_) {
      const auto wires = solid.face_wires(face);
      if (wires.empty()) throw std::runtime_error("face without boundary");
      origin_ = solid.vertex_point(solid.edge_first_vertex(wires[0][0].edge));
      Vec3 n = solid.face_normal(face, origin_);
      if (n.norm() < 0.5) throw std::runtime_error("no normal");
      e1_ = n.unitOrthogonal();
      e2_ = n.cross(e1_).normalized();
      return;
    }
    surface_ = std::make_unique<Surface>();
    surface_->surface = c.surface;
    surface_->analysis = new ShapeAnalysis_Surface(c.surface);
    umin_ = c.umin, umax_ = c.umax, vmin_ = c.vmin, vmax_ = c.vmax;
    gp_Pnt p;
    gp_Vec du, dv;
    c.surface->D1(0.5 * (umin_ + umax_), 0.5 * (vmin_ + vmax_), p, du, dv);
    // Scale (u, v) to lengths so that chart distances approximate surface distances.
    su_ = du.Magnitude() > 1e-12 ? du.Magnitude() : 1.0;
    sv_ = dv.Magnitude() > 1e-12 ? dv.Magnitude() : 1.0;
  } catch (const Standard_Failure& e) {
    throw std::runtime_error(std::string("cannot chart Face") + std::to_string(face.value()) +
                             ": " + e.GetMessageString());
  }
}

FaceChart::FaceChart(FaceChart&&) noexcept = default;
FaceChart::~FaceChart() = default;

Eigen::Vector2d FaceChart::to_chart(const Vec3& p) const {
  if (planar_) return {(p - origin_).dot(e1_), (p - origin_).dot(e2_)};
  try {
    gp_Pnt2d uv = surface_->analysis->ValueOfUV(gp_Pnt(p.x(), p.y(), p.z()), 1e-9);
    // On a periodic surface (u, v) is found within one period that need not be the face's
    // (a half cylinder over u in [pi, 2 pi]: its edge at 2 pi comes back at 0, across the
    // chart from the rest of its boundary): the period nearest the face's middle.
    double u = uv.X(), v = uv.Y();
    const Handle(Geom_Surface)& s = surface_->surface;
    if (s->IsUPeriodic()) u = nearest_period(u, 0.5 * (umin_ + umax_), s->UPeriod());
    if (s->IsVPeriodic()) v = nearest_period(v, 0.5 * (vmin_ + vmax_), s->VPeriod());
    return {u * su_, v * sv_};
  } catch (const Standard_Failure& e) {
    throw std::runtime_error(std::string("cannot find (u, v) of a point: ") + e.GetMessageString());
  }
}

Vec3 FaceChart::to_surface(const Eigen::Vector2d& q) const {
  if (planar_) return origin_ + q.x() * e1_ + q.y() * e2_;
  try {
    const gp_Pnt p = surface_->surface->Value(q.x() / su_, q.y() / sv_);
    return {p.X(), p.Y(), p.Z()};
  } catch (const Standard_Failure& e) {
    throw std::runtime_error(std::string("cannot evaluate a surface: ") + e.GetMessageString());
  }
}

}  // namespace vorohex::occ
