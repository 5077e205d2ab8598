// A modification of a solid that gives some of its faces new surfaces and nothing else (for
// OCCT's BRepTools_Modifier): edges keep their curves, vertices their points; what each user
// gives is the faces' curves on their new surfaces (NewCurve2d). The conversions of faces to
// the elementary surfaces they are use it (elementary_surfaces.h, canonical_surfaces.h).
#pragma once

#include <BRepTools_Modification.hxx>
#include <BRep_Tool.hxx>
#include <Geom_Surface.hxx>
#include <TopLoc_Location.hxx>
#include <TopoDS_Face.hxx>

#include <map>
#include <utility>

namespace vorohex::occ::detail {

class SurfaceSwap : public BRepTools_Modification {
 public:
  // New surfaces by face (TShape); `located`: each in its face's frame (the face keeps its
  // location), else in global coordinates (the face gets none).
  SurfaceSwap(std::map<const void*, Handle(Geom_Surface)> by_face, bool located)
      : by_face_(std::move(by_face)), located_(located) {}

  Standard_Boolean NewSurface(const TopoDS_Face& f, Handle(Geom_Surface) & s, TopLoc_Location& l,
                              Standard_Real& tol, Standard_Boolean& rev_wires,
                              Standard_Boolean& rev_face) override {
    const Handle(Geom_Surface)* n = surface_of(f);
    if (!n) return false;
    if (located_)
      BRep_Tool::Surface(f, l);
    else
      l = TopLoc_Location();
    s = *n;
    tol = BRep_Tool::Tolerance(f);
    rev_wires = rev_face = false;
    return true;
  }
  Standard_Boolean NewCurve(const TopoDS_Edge&, Handle(Geom_Curve) &, TopLoc_Location&,
                            Standard_Real&) override {
    return false;
  }
  Standard_Boolean NewPoint(const TopoDS_Vertex&, gp_Pnt&, Standard_Real&) override {
    return false;
  }
  Standard_Boolean NewParameter(const TopoDS_Vertex&, const TopoDS_Edge&, Standard_Real&,
                                Standard_Real&) override {
    return false;
  }
  GeomAbs_Shape Continuity(const TopoDS_Edge& e, const TopoDS_Face& f1, const TopoDS_Face& f2,
                           const TopoDS_Edge&, const TopoDS_Face&, const TopoDS_Face&) override {
    return BRep_Tool::Continuity(e, f1, f2);
  }

 protected:
  // The face's new surface, or null when it keeps its own.
  const Handle(Geom_Surface) * surface_of(const TopoDS_Face& f) const {
    auto it = by_face_.find(f.TShape().get());
    return it == by_face_.end() ? nullptr : &it->second;
  }

 private:
  std::map<const void*, Handle(Geom_Surface)> by_face_;
  bool located_;
};

}  // namespace vorohex::occ::detail
