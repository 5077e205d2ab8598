// What a mesher asks of the solid it meshes (issue 20): its faces, edges and vertices and
// their adjacency, point evaluation, projection, parametrisation (charts) and the kind of
// each surface and curve. occ::Solid implements it on an OCCT shape; a virtual-topology
// overlay (sub-volumes of a decomposition that are never cut out of the solid) implements
// it too, so no scheme needs a TopoDS_Solid of its own.
//
// Ids are 1-based; face_wires runs each wire with the face's material on its left seen from
// outside the solid (outer wire first).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "core/geometry.h"
#include "core/ids.h"

namespace vorohex::core {

// An edge of a face boundary as it is traversed (forward = from first to last vertex).
struct OrientedEdge {
  EdgeId edge;
  bool forward = true;
};

// The kind of a surface and what defines it (for schemes that look for axes): a plane's
// point and unit normal (its surface normal, not the face's side); a cylinder's, cone's,
// torus' or surface of revolution's axis point and unit direction; a sphere's centre; an
// extrusion's unit direction.
enum class SurfaceKind { plane, cylinder, cone, sphere, torus, revolution, extrusion, other };
struct SurfaceInfo {
  SurfaceKind kind = SurfaceKind::other;
  Vec3 origin = Vec3::Zero();
  Vec3 direction = Vec3::Zero();
  double radius = 0;  // cylinder, sphere, torus (major); cone at its origin
};

// The kind of a curve: a line (a point and unit direction), a circle (centre, unit normal,
// radius), or another curve.
enum class CurveKind { line, circle, other };
struct CurveInfo {
  CurveKind kind = CurveKind::other;
  Vec3 origin = Vec3::Zero();
  Vec3 direction = Vec3::Zero();
  double radius = 0;
};

// A 2-D chart of one face: its plane for planar faces, its scaled (u, v) otherwise. It may
// be mirrored with respect to the face's outward normal.
class SurfaceChart {
 public:
  virtual ~SurfaceChart() = default;
  virtual Eigen::Vector2d to_chart(const Vec3& p) const = 0;    // p on or near the face
  virtual Vec3 to_surface(const Eigen::Vector2d& q) const = 0;  // the surface point of q
  virtual bool planar() const = 0;
};

class MeshDomain {
 public:
  virtual ~MeshDomain() = default;

  // Topology --------------------------------------------------------------------------
  virtual int num_faces() const = 0;
  virtual int num_edges() const = 0;
  virtual int num_vertices() const = 0;
  std::vector<FaceId> faces() const;  // 1..num_faces
  std::vector<EdgeId> edges() const;
  std::vector<VertexId> vertices() const;
  virtual std::vector<std::vector<OrientedEdge>> face_wires(FaceId f) const = 0;
  virtual std::vector<FaceId> edge_faces(EdgeId e) const = 0;
  virtual VertexId edge_first_vertex(EdgeId e) const = 0;  // in the edge's own direction
  virtual VertexId edge_last_vertex(EdgeId e) const = 0;
  virtual bool edge_is_degenerated(EdgeId e) const = 0;  // e.g. a sphere's pole

  // Geometry --------------------------------------------------------------------------
  virtual double volume() const = 0;
  virtual double area(FaceId f) const = 0;
  virtual BoundingBox bounding_box() const = 0;
  // A box holding the face or edge (not necessarily tight).
  virtual BoundingBox face_bounding_box(FaceId f) const = 0;
  virtual BoundingBox edge_bounding_box(EdgeId e) const = 0;
  double diagonal() const { return bounding_box().diagonal(); }
  // The largest vertex, edge or face tolerance: closer geometry counts as coincident.
  virtual double tolerance() const = 0;
  virtual bool face_is_planar(FaceId f) const = 0;
  virtual Vec3 vertex_point(VertexId v) const = 0;
  virtual double edge_length(EdgeId e) const = 0;
  // n+1 points dividing the edge into n segments of equal arc length, first to last vertex.
  virtual std::vector<Vec3> edge_points_by_length(EdgeId e, int n) const = 0;
  virtual Vec3 project_to_face(FaceId f, const Vec3& p) const = 0;  // nearest point of the face
  virtual Vec3 project_to_edge(EdgeId e, const Vec3& p) const = 0;
  double distance_to_face(FaceId f, const Vec3& p) const {
    return (project_to_face(f, p) - p).norm();
  }
  double distance_to_edge(EdgeId e, const Vec3& p) const {
    return (project_to_edge(e, p) - p).norm();
  }
  double distance_to_vertex(VertexId v, const Vec3& p) const {
    return (vertex_point(v) - p).norm();
  }
  virtual FaceId nearest_face(const Vec3& p) const = 0;  // ties: the lowest id
  virtual EdgeId nearest_edge(const Vec3& p) const = 0;
  // Outward unit normal of face f at its point nearest to p.
  virtual Vec3 face_normal(FaceId f, const Vec3& p) const = 0;
  virtual SurfaceInfo surface_info(FaceId f) const = 0;
  virtual CurveInfo curve_info(EdgeId e) const = 0;
  // Throws std::runtime_error when the face cannot be charted.
  virtual std::unique_ptr<SurfaceChart> face_chart(FaceId f) const = 0;
};

inline std::vector<FaceId> MeshDomain::faces() const {
  std::vector<FaceId> ids;
  for (int i = 1; i <= num_faces(); ++i) ids.emplace_back(i);
  return ids;
}
inline std::vector<EdgeId> MeshDomain::edges() const {
  std::vector<EdgeId> ids;
  for (int i = 1; i <= num_edges(); ++i) ids.emplace_back(i);
  return ids;
}
inline std::vector<VertexId> MeshDomain::vertices() const {
  std::vector<VertexId> ids;
  for (int i = 1; i <= num_vertices(); ++i) ids.emplace_back(i);
  return ids;
}

}  // namespace vorohex::core
