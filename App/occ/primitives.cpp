#include "occ/primitives.h"

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepGProp.hxx>
#include <BRepLib.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepPrimAPI_MakeRevol.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <GProp_GProps.hxx>
#include <STEPControl_Writer.hxx>
#include <ShapeCustom.hxx>
#include <ShapeFix_Face.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Ax1.hxx>
#include <gp_Ax2.hxx>
#include <gp_Circ.hxx>
#include <gp_Vec.hxx>

#include <cmath>
#include <stdexcept>
#include <string>

#include "occ/detail/fixtures.h"
#include "occ/solid_impl.h"

namespace vorohex::occ {
namespace {

gp_Pnt pnt(const Vec3& p) {
  return gp_Pnt(p.x(), p.y(), p.z());
}

TopoDS_Solid first_solid(const TopoDS_Shape& shape, const char* what) {
  TopExp_Explorer ex(shape, TopAbs_SOLID);
  if (!ex.More()) throw std::runtime_error(std::string(what) + ": OCCT produced no solid");
  return TopoDS::Solid(ex.Current());
}

// Turns an inside-out solid so its volume is positive.
void orient(TopoDS_Solid& solid) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(solid, props);
  if (props.Mass() < 0) BRepLib::OrientClosedSolid(solid);
}

template <class F>
Solid guarded(const char* what, F&& build) {
  try {
    return make_solid(build());
  } catch (const Standard_Failure& e) {
    throw std::runtime_error(std::string(what) + " failed: " + e.GetMessageString());
  }
}

TopoDS_Wire polygon_wire(const std::vector<std::array<double, 2>>& pts, double z) {
  BRepBuilderAPI_MakePolygon poly;
  for (const auto& p : pts) poly.Add(gp_Pnt(p[0], p[1], z));
  poly.Close();
  if (!poly.IsDone()) throw std::invalid_argument("degenerate polygon");
  return poly.Wire();
}

}  // namespace

Solid make_box(double dx, double dy, double dz) {
  if (!(dx > 0 && dy > 0 && dz > 0))
    throw std::invalid_argument("make_box needs positive dimensions");
  return guarded("make_box", [&] { return BRepPrimAPI_MakeBox(dx, dy, dz).Solid(); });
}

Solid make_tapered_brick(double dx, double dy, double dz, double taper) {
  if (!(dx > 0 && dy > 0 && dz > 0) || !(taper >= 0) || 2 * taper >= std::min(dx, dy))
    throw std::invalid_argument(
        "make_tapered_brick needs positive sizes and 2*taper < min(dx, dy)");
  const double t = taper;
  const std::vector<Vec3> p = {{0, 0, 0},  {dx, 0, 0},      {dx, dy, 0},          {0, dy, 0},
                               {t, t, dz}, {dx - t, t, dz}, {dx - t, dy - t, dz}, {t, dy - t, dz}};
  const std::vector<std::vector<int>> f = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                           {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  return make_polyhedron(p, f);
}

Solid make_polyhedron(const std::vector<Vec3>& points, const std::vector<std::vector<int>>& faces) {
  return guarded("make_polyhedron", [&] {
    BRepBuilderAPI_Sewing sewing(1e-6);
    for (const auto& face : faces) {
      if (face.size() < 3) throw std::invalid_argument("make_polyhedron: a face has < 3 points");
      BRepBuilderAPI_MakePolygon poly;
      for (int i : face) {
        if (i < 0 || i >= static_cast<int>(points.size()))
          throw std::invalid_argument("make_polyhedron: point index out of range");
        poly.Add(pnt(points[i]));
      }
      poly.Close();
      BRepBuilderAPI_MakeFace mf(poly.Wire(), true);
      if (!mf.IsDone()) throw std::invalid_argument("make_polyhedron: a face is not planar");
      sewing.Add(mf.Face());
    }
    sewing.Perform();
    TopExp_Explorer ex(sewing.SewedShape(), TopAbs_SHELL);
    if (!ex.More()) throw std::runtime_error("make_polyhedron: sewing gave no shell");
    BRepBuilderAPI_MakeSolid ms(TopoDS::Shell(ex.Current()));
    TopoDS_Solid solid = ms.Solid();
    BRepLib::OrientClosedSolid(solid);
    orient(solid);
    return solid;
  });
}

Solid make_prism(const std::vector<std::array<double, 2>>& outline, double depth,
                 const std::vector<std::vector<std::array<double, 2>>>& holes) {
  if (!(depth > 0) || outline.size() < 3)
    throw std::invalid_argument("make_prism needs >= 3 outline points and depth > 0");
  return guarded("make_prism", [&] {
    BRepBuilderAPI_MakeFace mf(polygon_wire(outline, 0.0), true);
    for (const auto& hole : holes) mf.Add(polygon_wire(hole, 0.0));
    // Holes may come in any orientation: let ShapeFix orient the wires.
    ShapeFix_Face fix(mf.Face());
    fix.FixOrientation();
    TopoDS_Solid solid =
        first_solid(BRepPrimAPI_MakePrism(fix.Face(), gp_Vec(0, 0, depth)).Shape(), "make_prism");
    orient(solid);
    return solid;
  });
}

Solid make_cylinder(double radius, double height) {
  if (!(radius > 0 && height > 0))
    throw std::invalid_argument("make_cylinder needs positive radius and height");
  return guarded("make_cylinder", [&] { return BRepPrimAPI_MakeCylinder(radius, height).Solid(); });
}

Solid make_box(double dx, double dy, double dz, const Vec3& corner) {
  if (!(dx > 0 && dy > 0 && dz > 0))
    throw std::invalid_argument("make_box needs positive dimensions");
  return guarded("make_box", [&] { return BRepPrimAPI_MakeBox(pnt(corner), dx, dy, dz).Solid(); });
}

Solid make_cylinder(double radius, double height, const Vec3& base, const Vec3& axis) {
  if (!(radius > 0 && height > 0) || !(axis.norm() > 0))
    throw std::invalid_argument("make_cylinder needs positive radius and height and an axis");
  return guarded("make_cylinder", [&] {
    const gp_Ax2 frame(pnt(base), gp_Dir(axis.x(), axis.y(), axis.z()));
    return BRepPrimAPI_MakeCylinder(frame, radius, height).Solid();
  });
}

Solid make_cone(double r1, double r2, double height, const Vec3& base, const Vec3& axis) {
  if (!(r1 >= 0 && r2 >= 0 && r1 + r2 > 0 && r1 != r2 && height > 0) || !(axis.norm() > 0))
    throw std::invalid_argument("make_cone needs radii >= 0 (different), a height and an axis");
  return guarded("make_cone", [&] {
    const gp_Ax2 frame(pnt(base), gp_Dir(axis.x(), axis.y(), axis.z()));
    return BRepPrimAPI_MakeCone(frame, r1, r2, height).Solid();
  });
}

Solid make_torus(double major, double minor, const Vec3& centre, const Vec3& axis) {
  if (!(minor > 0 && major > minor) || !(axis.norm() > 0))
    throw std::invalid_argument("make_torus needs 0 < minor < major and an axis");
  return guarded("make_torus", [&] {
    const gp_Ax2 frame(pnt(centre), gp_Dir(axis.x(), axis.y(), axis.z()));
    return BRepPrimAPI_MakeTorus(frame, major, minor).Solid();
  });
}

Solid make_revolved(const std::vector<std::array<double, 2>>& rz) {
  if (rz.size() < 3) throw std::invalid_argument("make_revolved needs a polygon");
  for (const auto& q : rz)
    if (!(q[0] >= 0)) throw std::invalid_argument("make_revolved needs r >= 0");
  return guarded("make_revolved", [&] {
    BRepBuilderAPI_MakePolygon poly;
    for (const auto& q : rz) poly.Add(gp_Pnt(q[0], 0, q[1]));
    poly.Close();
    const TopoDS_Face face = BRepBuilderAPI_MakeFace(poly.Wire(), true).Face();
    const gp_Ax1 axis(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1));
    return first_solid(BRepPrimAPI_MakeRevol(face, axis).Shape(), "make_revolved");
  });
}

Solid make_ring_sector(double inner_radius, double outer_radius, double angle, double depth) {
  if (!(inner_radius > 0 && outer_radius > inner_radius && angle > 0 && angle < 2 * M_PI &&
        depth > 0))
    throw std::invalid_argument("make_ring_sector needs 0 < inner < outer, 0 < angle < 2 pi");
  return guarded("make_ring_sector", [&] {
    const double c = std::cos(angle), s = std::sin(angle), h = std::cos(angle / 2),
                 k = std::sin(angle / 2);
    const gp_Pnt a(inner_radius, 0, 0), b(outer_radius, 0, 0);
    const gp_Pnt bc(outer_radius * c, outer_radius * s, 0),
        ac(inner_radius * c, inner_radius * s, 0);
    BRepBuilderAPI_MakeWire wire;
    wire.Add(BRepBuilderAPI_MakeEdge(a, b).Edge());
    wire.Add(BRepBuilderAPI_MakeEdge(
                 GC_MakeArcOfCircle(b, gp_Pnt(outer_radius * h, outer_radius * k, 0), bc).Value())
                 .Edge());
    wire.Add(BRepBuilderAPI_MakeEdge(bc, ac).Edge());
    wire.Add(BRepBuilderAPI_MakeEdge(
                 GC_MakeArcOfCircle(ac, gp_Pnt(inner_radius * h, inner_radius * k, 0), a).Value())
                 .Edge());
    BRepBuilderAPI_MakeFace mf(wire.Wire(), true);
    TopoDS_Solid solid = first_solid(BRepPrimAPI_MakePrism(mf.Face(), gp_Vec(0, 0, depth)).Shape(),
                                     "make_ring_sector");
    orient(solid);
    return solid;
  });
}

namespace detail {

bool write_fixture(Fixture kind, const std::string& path) {
  try {
    const TopoDS_Solid box = BRepPrimAPI_MakeBox(1, 1, 1).Solid();
    BRep_Builder b;
    TopoDS_Shape shape;
    if (kind == Fixture::revolved_cylinder) {
      shape = ShapeCustom::ConvertToRevolution(BRepPrimAPI_MakeCylinder(2, 5).Solid());
    } else if (kind == Fixture::bspline_half_cylinder) {
      BRepBuilderAPI_NurbsConvert nurbs(BRepPrimAPI_MakeCylinder(2, 5, M_PI).Solid(), true);
      shape = nurbs.Shape();
    } else if (kind == Fixture::bspline_flanged_pipe) {
      const TopoDS_Shape body = BRepAlgoAPI_Fuse(BRepPrimAPI_MakeCylinder(10, 40).Solid(),
                                                 BRepPrimAPI_MakeCylinder(20, 6).Solid())
                                    .Shape();
      ShapeUpgrade_UnifySameDomain unify(body);
      unify.Build();
      const TopoDS_Shape pipe =
          BRepAlgoAPI_Cut(unify.Shape(), BRepPrimAPI_MakeCylinder(6, 40).Solid()).Shape();
      BRepBuilderAPI_NurbsConvert nurbs(pipe, true);
      shape = nurbs.Shape();
    } else if (kind == Fixture::bspline_tube) {
      const TopoDS_Shape tube = BRepAlgoAPI_Cut(BRepPrimAPI_MakeCylinder(2, 5).Solid(),
                                                BRepPrimAPI_MakeCylinder(1, 5).Solid())
                                    .Shape();
      BRepBuilderAPI_NurbsConvert nurbs(tube, true);
      shape = nurbs.Shape();
    } else if (kind == Fixture::revolved_cone) {
      shape = ShapeCustom::ConvertToRevolution(BRepPrimAPI_MakeCone(3, 1, 4).Solid());
    } else if (kind == Fixture::bad_tolerance_box) {
      TopExp_Explorer ex(box, TopAbs_VERTEX);
      const TopoDS_Vertex v = TopoDS::Vertex(ex.Current());
      const gp_Pnt p = BRep_Tool::Pnt(v);
      b.UpdateVertex(v, gp_Pnt(p.X() + 1e-4, p.Y() + 1e-4, p.Z()), 1e-7);
      shape = box;
    } else if (kind == Fixture::self_intersecting_prism) {
      BRepBuilderAPI_MakePolygon bowtie(gp_Pnt(0, 0, 0), gp_Pnt(2, 1, 0), gp_Pnt(2, 0, 0),
                                        gp_Pnt(0, 1, 0), true);
      const TopoDS_Face face = BRepBuilderAPI_MakeFace(bowtie.Wire(), true).Face();
      shape = BRepPrimAPI_MakePrism(face, gp_Vec(0, 0, 1)).Shape();
    } else if (kind == Fixture::open_box_shell || kind == Fixture::closed_box_shell) {
      TopoDS_Shell shell;
      b.MakeShell(shell);
      int n = 0;
      for (TopExp_Explorer ex(box, TopAbs_FACE); ex.More(); ex.Next(), ++n)
        if (kind == Fixture::closed_box_shell || n != 5) b.Add(shell, ex.Current());
      shell.Closed(kind == Fixture::closed_box_shell);
      shape = shell;
    } else {
      TopoDS_Compound compound;
      b.MakeCompound(compound);
      if (kind == Fixture::two_boxes || kind == Fixture::touching_boxes ||
          kind == Fixture::overlapping_boxes) {
        const double x = kind == Fixture::two_boxes ? 3 : kind == Fixture::touching_boxes ? 1 : 0.5;
        b.Add(compound, box);
        b.Add(compound, BRepPrimAPI_MakeBox(gp_Pnt(x, 0, 0), 1, 1, 1).Solid());
      } else if (kind == Fixture::edge_touching_boxes || kind == Fixture::vertex_touching_boxes) {
        b.Add(compound, box);
        const double z = kind == Fixture::edge_touching_boxes ? 0 : 1;
        b.Add(compound, BRepPrimAPI_MakeBox(gp_Pnt(1, 1, z), 1, 1, 1).Solid());
      } else if (kind == Fixture::stacked_boxes) {
        b.Add(compound, BRepPrimAPI_MakeBox(2, 1, 1).Solid());
        b.Add(compound, BRepPrimAPI_MakeBox(gp_Pnt(0.5, 0, 1), 1, 1, 1).Solid());
      } else {
        int n = 0;
        for (TopExp_Explorer ex(box, TopAbs_FACE); ex.More() && n < 3; ex.Next(), ++n)
          b.Add(compound, ex.Current());
      }
      shape = compound;
    }
    const std::string ext = path.size() >= 5 ? path.substr(path.size() - 5) : path;
    if (ext == ".step" || path.substr(path.size() - 4) == ".stp") {
      STEPControl_Writer writer;
      return writer.Transfer(shape, STEPControl_AsIs) == IFSelect_RetDone &&
             writer.Write(path.c_str()) == IFSelect_RetDone;
    }
    return BRepTools::Write(shape, path.c_str());
  } catch (const Standard_Failure&) {
    return false;
  }
}

}  // namespace detail
}  // namespace vorohex::occ
