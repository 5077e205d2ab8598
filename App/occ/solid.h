// A CAD solid with indexed topology and geometry queries. The only place OCCT types live
// is behind this pimpl (and in occ/*.cpp), so no other stage includes TopoDS/BRep headers.
//
// Entity ids are the 1-based TopExp::MapShapes indices of the solid (FaceId{7} == "Face7").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "core/ids.h"
#include "core/mesh_domain.h"

namespace vorohex::occ {

using core::BoundingBox;
using core::EdgeId;
using core::FaceId;
using core::Vec3;
using core::VertexId;

using core::OrientedEdge;

// A solid (or several glued at their common faces) read from CAD: the MeshDomain every
// mesher works on, over an OCCT shape.
class Solid : public core::MeshDomain {
 public:
  struct Impl;  // holds the TopoDS_Solid and its MapShapes maps (occ/solid_impl.h)

  explicit Solid(std::unique_ptr<Impl> impl);
  Solid(Solid&&) noexcept;
  Solid& operator=(Solid&&) noexcept;
  ~Solid();

  // A copy sharing the same (immutable) OCCT shape.
  Solid clone() const;

  // Topology ------------------------------------------------------------------------
  int num_faces() const override;
  int num_edges() const override;
  int num_vertices() const override;

  // The wires of a face: outer first, each a closed cycle of oriented edges in order,
  // oriented so that the face material lies on the left seen from outside the solid.
  std::vector<std::vector<OrientedEdge>> face_wires(FaceId f) const override;
  std::vector<FaceId> edge_faces(EdgeId e) const override;  // faces an edge bounds
  VertexId edge_first_vertex(EdgeId e) const override;      // in the edge's own orientation
  VertexId edge_last_vertex(EdgeId e) const override;
  bool edge_is_degenerated(EdgeId e) const override;  // e.g. a sphere's pole

  // Geometry ------------------------------------------------------------------------
  double volume() const override;
  double area(FaceId f) const override;
  BoundingBox bounding_box() const override;  // tight (optimal) box
  BoundingBox face_bounding_box(FaceId f) const override;
  BoundingBox edge_bounding_box(EdgeId e) const override;
  bool face_is_planar(FaceId f) const override;

  Vec3 vertex_point(VertexId v) const override;
  double edge_length(EdgeId e) const override;
  // n+1 points dividing the edge into n segments of equal arc length, from its first to
  // its last vertex (end points are exactly the vertex points).
  std::vector<Vec3> edge_points_by_length(EdgeId e, int n) const override;

  // Closest point on the face (its trimmed extent), and the distance to it.
  Vec3 project_to_face(FaceId f, const Vec3& p) const override;
  Vec3 project_to_edge(EdgeId e, const Vec3& p) const override;
  // Distance to the whole boundary (nearest face), for meshes made by other tools.
  double distance_to_boundary(const Vec3& p) const;
  // OCCT's largest vertex, edge or face tolerance: geometry closer than this counts as
  // coincident (a healed solid can have tolerances well above the default 1e-7).
  double tolerance() const override;
  // The face / edge nearest to p (ties: the lowest index).
  FaceId nearest_face(const Vec3& p) const override;
  EdgeId nearest_edge(const Vec3& p) const override;
  // Outward unit normal of face f at the point of the face nearest to p.
  Vec3 face_normal(FaceId f, const Vec3& p) const override;
  // Interior angle of the solid across edge e at its point p, where `tangent` is the edge's
  // direction (in its own orientation), radians in [0, 2 pi]: below pi convex, above concave
  // (3 pi / 2 at the inner corner of an L), pi where the faces are tangent; NaN for a seam
  // or an edge that does not bound two faces.
  double interior_angle(EdgeId e, const Vec3& p, const Vec3& tangent) const;
  core::SurfaceInfo surface_info(FaceId f) const override;
  core::CurveInfo curve_info(EdgeId e) const override;
  std::unique_ptr<core::SurfaceChart> face_chart(FaceId f) const override;

  // Several solids ------------------------------------------------------------------
  // A Solid may hold several solids glued at the faces they have in common (read with
  // ReadOptions::several_solids); ids then number the entities of all of them, a common
  // face once. A plain solid has num_solids() == 1.
  int num_solids() const;
  Solid part(int k) const;  // the k-th solid (0-based) as a Solid of its own
  // The id here of each entity of `part` of dimension `dim` (0 vertex, 1 edge, 2 face),
  // indexed by its id in `part` (entry 0 unused; 0 = not an entity of this shape).
  std::vector<int> part_ids(const Solid& part, int dim) const;
  bool face_is_interface(FaceId f) const;  // the face bounds two of the solids
  int num_interface_faces() const;

  // Serialisation (FreeCAD's Part.Shape.exportBrepToString gives this format).
  std::string to_brep_string() const;

  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace vorohex::occ
