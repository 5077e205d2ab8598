// BRepModel: the topology and the linear approximation of a solid as the Voronoi stage
// needs them (paper §2): faces, edges and vertices with their FreeCAD ids, incidence and
// adjacency, convex and concave edges and vertices, and a polyhedral approximation whose
// every polygon, segment and point is tagged with the model entity it comes from.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "core/geometry.h"
#include "core/ids.h"
#include "occ/solid.h"

namespace vorohex::model {

using core::EdgeId;
using core::FaceId;
using core::Vec3;
using core::VertexId;

enum class EntityKind { face, edge, vertex };

// A model entity of any kind, e.g. {face, 7} is "Face7".
struct EntityRef {
  EntityKind kind = EntityKind::face;
  int id = 0;  // the 1-based MapShapes index
  std::string name() const;
  friend bool operator==(EntityRef a, EntityRef b) { return a.kind == b.kind && a.id == b.id; }
  friend bool operator!=(EntityRef a, EntityRef b) { return !(a == b); }
  friend bool operator<(EntityRef a, EntityRef b) {
    return a.kind != b.kind ? a.kind < b.kind : a.id < b.id;
  }
};
inline EntityRef ref(FaceId f) {
  return {EntityKind::face, f.value()};
}
inline EntityRef ref(EdgeId e) {
  return {EntityKind::edge, e.value()};
}
inline EntityRef ref(VertexId v) {
  return {EntityKind::vertex, v.value()};
}

struct ModelOptions {
  // Chord tolerance of the linearisation of curved faces and edges, relative to the
  // bounding-box diagonal (dimensionless).
  double linear_tolerance = 0.005;
  // Maximum angle between the normals of neighbouring facets, radians.
  double angular_tolerance = 0.35;
  // Edges whose dihedral angle is within this of pi (radians) are smooth, not convex or
  // concave (tangent-continuous faces, seams).
  double smooth_angle = 0.05;
  // Empty if valid, else the reason.
  std::string validate() const;
};

enum class Convexity { convex, concave, smooth };
const char* convexity_name(Convexity c);

struct ModelFace {
  FaceId id;
  bool planar = false;
  Vec3 normal{0, 0, 0};                               // outward unit normal if planar
  std::vector<std::vector<occ::OrientedEdge>> wires;  // outer first (see occ::Solid)
  std::vector<EdgeId> edges;                          // distinct bounding edges
  std::vector<VertexId> vertices;                     // distinct vertices
};

struct ModelEdge {
  EdgeId id;
  VertexId first, last;       // end vertices (equal for a closed edge)
  std::vector<FaceId> faces;  // faces it bounds (one for a seam)
  bool degenerated = false;
  // Interior angle of the solid across the edge at its middle, radians in (0, 2 pi):
  // < pi convex, > pi concave (e.g. 3 pi / 2 at the inner corner of an L).
  double dihedral = 3.14159265358979323846;
  Convexity convexity = Convexity::smooth;
};

struct ModelVertex {
  VertexId id;
  Vec3 point{0, 0, 0};
  std::vector<EdgeId> edges;
  std::vector<FaceId> faces;
  // A ball inside the solid can touch the boundary at this vertex alone (e.g. the inner
  // corner of a box cut from a bigger box), so the vertex governs an interior region.
  bool concave = false;
};

// The polyhedral approximation. Point indices refer to `points` (welded: a point shared
// by faces and edges appears once).
struct LinearPolygon {
  EntityRef origin;                     // the model face it approximates
  Vec3 normal{0, 0, 0};                 // outward unit normal
  std::vector<std::vector<int>> loops;  // outer first; counter-clockwise seen from outside
  // A triangulation of the polygon (planar faces only), for queries that prefer small
  // pieces over one polygon of many sides.
  std::vector<std::array<int, 3>> triangles;
};
struct LinearSegment {
  int a = 0, b = 0;
  EntityRef origin;      // a model edge, or a face for segments inside a curved face
  bool concave = false;  // the solid's interior angle across it exceeds pi (any bend)
};
struct LinearPoint {
  int point = 0;
  EntityRef origin;      // a model vertex, edge (inner polyline point) or face
  bool concave = false;  // see ModelVertex::concave
};
struct Linearization {
  std::vector<Vec3> points;
  std::vector<LinearPolygon> polygons;  // planar faces whole (with holes); facets otherwise
  std::vector<LinearSegment> segments;  // every polygon side, once
  std::vector<LinearPoint> corners;     // every point, once
};

class BRepModel {
 public:
  // Throws std::runtime_error if the solid cannot be tessellated (OCCT failure).
  BRepModel(const occ::Solid& solid, const ModelOptions& options);

  const std::vector<ModelFace>& faces() const { return faces_; }  // [i] has id i+1
  const std::vector<ModelEdge>& edges() const { return edges_; }
  const std::vector<ModelVertex>& vertices() const { return vertices_; }
  const ModelFace& face(FaceId f) const { return faces_.at(f.value() - 1); }
  const ModelEdge& edge(EdgeId e) const { return edges_.at(e.value() - 1); }
  const ModelVertex& vertex(VertexId v) const { return vertices_.at(v.value() - 1); }
  int num_entities() const { return int(faces_.size() + edges_.size() + vertices_.size()); }

  // Dense index of an entity: faces first, then edges, then vertices (0-based).
  int index(EntityRef e) const;
  EntityRef entity(int index) const;

  // Paper §2: a is incident on b iff a is an end vertex of edge b, a vertex of face b or
  // a bounding edge of face b. Symmetric here ("incident one on the other").
  bool incident(EntityRef a, EntityRef b) const;
  // Not incident, distinct, and some third entity is incident on both (e.g. two faces
  // sharing a vertex or an edge, a face and an edge sharing a vertex).
  bool adjacent(EntityRef a, EntityRef b) const;
  // Neither equal, incident nor adjacent (the paper's "unconnected").
  bool unconnected(EntityRef a, EntityRef b) const;
  // Whether the entity can be the nearest boundary entity of interior points: faces,
  // concave edges and concave vertices.
  bool governs_interior(EntityRef e) const;

  const Linearization& linear() const { return linear_; }
  core::BoundingBox bounding_box() const { return box_; }
  double diagonal() const { return box_.diagonal(); }
  const ModelOptions& options() const { return options_; }

 private:
  const std::vector<int>& related(EntityRef e) const { return related_[index(e)]; }

  ModelOptions options_;
  std::vector<ModelFace> faces_;
  std::vector<ModelEdge> edges_;
  std::vector<ModelVertex> vertices_;
  std::vector<std::vector<int>> related_;  // sorted dense indices incident either way
  Linearization linear_;
  core::BoundingBox box_;
};

struct ModelResult {
  std::unique_ptr<BRepModel> model;  // null on failure
  std::vector<core::Diagnostic> diagnostics;
  bool ok() const { return model != nullptr; }
};

// Builds the model; invalid options or OCCT failures become error diagnostics.
ModelResult build_model(const occ::Solid& solid, const ModelOptions& options = {});

}  // namespace vorohex::model
