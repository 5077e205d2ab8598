#include "occ/tessellate.h"

#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Poly_PolygonOnTriangulation.hxx>
#include <Poly_Triangulation.hxx>
#include <Standard_Failure.hxx>
#include <TopLoc_Location.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>

#include <algorithm>

#include "occ/solid_impl.h"

namespace vorohex::occ {
namespace {

Vec3 to_vec(const gp_Pnt& p) {
  return Vec3(p.X(), p.Y(), p.Z());
}

}  // namespace

Tessellation tessellate(const Solid& solid, const TessellationOptions& options) {
  Tessellation out;
  const Solid::Impl& impl = solid.impl();
  const int nf = impl.faces.Extent(), ne = impl.edges.Extent();
  out.faces.resize(nf + 1);
  out.edge_polylines.resize(ne + 1);
  try {
    // OCCT keeps a face's triangulation on the shape and does not redo it when it is finer
    // than asked: without this the result would depend on earlier calls (the grid mesher's
    // fine tessellation gave the tet split's second chance another surface, and on HexMe
    // i23 inverted hexes where the tet split alone is valid).
    BRepTools::Clean(impl.solid);
    BRepMesh_IncrementalMesh mesher(impl.solid, options.linear_deflection, false,
                                    options.angular_deflection, false);
    if (!mesher.IsDone()) {
      out.error = "OCCT's mesher did not finish";
      return out;
    }
    for (int i = 1; i <= nf; ++i) {
      const TopoDS_Face& f = TopoDS::Face(impl.faces(i));
      FaceTriangulation& ft = out.faces[i];
      ft.face = FaceId(i);
      TopLoc_Location loc;
      const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(f, loc);
      if (tri.IsNull()) {
        out.error = "Face" + std::to_string(i) + " has no triangulation";
        return out;
      }
      const gp_Trsf trsf = loc.Transformation();
      ft.nodes.reserve(tri->NbNodes());
      for (int n = 1; n <= tri->NbNodes(); ++n)
        ft.nodes.push_back(to_vec(tri->Node(n).Transformed(trsf)));
      const bool reversed = f.Orientation() == TopAbs_REVERSED;
      for (int t = 1; t <= tri->NbTriangles(); ++t) {
        int a, b, c;
        tri->Triangle(t).Get(a, b, c);
        if (reversed) std::swap(b, c);
        ft.triangles.push_back({a - 1, b - 1, c - 1});
      }
    }
    for (int i = 1; i <= ne; ++i) {
      const TopoDS_Edge& e = TopoDS::Edge(impl.edges(i));
      const EdgeCache& ec = impl.edge(i);
      const Vec3 p0 = to_vec(ec.p_first), p1 = to_vec(ec.p_last);
      std::vector<Vec3>& poly = out.edge_polylines[i];
      if (BRep_Tool::Degenerated(e)) {
        poly.push_back(p0);
        continue;
      }
      for (int f : (*impl.edge_faces)[i]) {
        TopLoc_Location loc;
        const TopoDS_Face& face = TopoDS::Face(impl.faces(f));
        const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, loc);
        if (tri.IsNull()) continue;
        const Handle(Poly_PolygonOnTriangulation) pt =
            BRep_Tool::PolygonOnTriangulation(e, tri, loc);
        if (pt.IsNull()) continue;
        const gp_Trsf trsf = loc.Transformation();
        for (int k = 1; k <= pt->NbNodes(); ++k)
          poly.push_back(to_vec(tri->Node(pt->Node(k)).Transformed(trsf)));
        break;
      }
      if (poly.size() < 2) {
        poly = solid.edge_points_by_length(EdgeId(i), 1);
        continue;
      }
      // Orient from the first vertex and make the ends exactly the vertex points.
      if ((poly.front() - p0).norm() + (poly.back() - p1).norm() >
          (poly.front() - p1).norm() + (poly.back() - p0).norm())
        std::reverse(poly.begin(), poly.end());
      poly.front() = p0;
      poly.back() = p1;
    }
  } catch (const Standard_Failure& e) {
    out.error = std::string("OCCT failed to tessellate the solid: ") + e.GetMessageString();
  }
  return out;
}

}  // namespace vorohex::occ
