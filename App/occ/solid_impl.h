// Private to App/occ: the OCCT side of occ::Solid. Everything a query needs is computed once
// (at construction, or on the first question, guarded: a face classifier's raster) and never
// changed, so const queries are safe from several threads.
#pragma once

#include <Bnd_Box.hxx>
#include <Geom_Curve.hxx>
#include <Geom_Surface.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Shape.hxx>
#include <TopoDS_Solid.hxx>
#include <gp_Pln.hxx>
#include <gp_Pnt.hxx>

#include <memory>
#include <mutex>
#include <vector>

#include "occ/solid.h"

namespace vorohex::occ {
namespace detail {
class FaceClassifier;
}

// Per-face data for fast projection (index 0 unused so that FaceId indexes directly).
struct FaceCache {
  Handle(Geom_Surface) surface;  // untrimmed, located surface
  double umin = 0, umax = 0, vmin = 0, vmax = 0;
  bool planar = false;    // flat (possibly a B-spline that happens to be flat)
  bool is_plane = false;  // a Geom_Plane: projections take the fast path
  gp_Pln plane;           // when is_plane (normal as the surface's, not the face's)
  bool reversed = false;  // face orientation in the solid is REVERSED
  double tolerance = 1e-7;
  Bnd_Box box;
  std::shared_ptr<const detail::FaceClassifier> classifier;  // point-in-face in (u, v)
  std::vector<int> edges;                                    // edge ids of the face boundary
};

struct EdgeCache {
  Handle(Geom_Curve) curve;  // null for degenerated edges
  double first = 0, last = 0;
  bool line = false;
  gp_Pnt p_first, p_last;  // vertex points of edge_first_vertex / edge_last_vertex
  int v_first = 0, v_last = 0;
  Bnd_Box box;
};

// A value computed on the first question and kept (guarded: const queries may come from
// several threads).
struct LazyValue {
  std::once_flag once;
  double value = 0;
};

struct Solid::Impl {
  TopoDS_Shape solid;                // a solid, or a compound of solids sharing common faces
  std::vector<TopoDS_Solid> parts;   // the solids (one for a plain solid)
  std::vector<char> interface_face;  // by face id: the face bounds two of the parts
  TopTools_IndexedMapOfShape faces, edges, vertices;
  // Immutable caches shared by clones.
  std::shared_ptr<const std::vector<FaceCache>> face_cache;
  std::shared_ptr<const std::vector<EdgeCache>> edge_cache;
  std::shared_ptr<const std::vector<std::vector<int>>> edge_faces;
  // The volume, an adaptive integration that takes seconds on B-spline faces (HexMe i08:
  // about a second per call, which the grid mesher made six times).
  std::shared_ptr<LazyValue> volume = std::make_shared<LazyValue>();

  const FaceCache& face(int i) const { return (*face_cache)[i]; }
  const EdgeCache& edge(int i) const { return (*edge_cache)[i]; }
};

// Builds the maps and caches of a solid (throws Standard_Failure from OCCT on bad input).
// A compound must hold solids only (glued, shape_io); entity ids number all of them.
std::unique_ptr<Solid::Impl> make_solid_impl(const TopoDS_Shape& solid);

inline Solid make_solid(const TopoDS_Solid& solid) {
  return Solid(make_solid_impl(solid));
}

}  // namespace vorohex::occ
