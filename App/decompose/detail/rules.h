// The combinatorial part of the decomposition (paper §4.2-4.3), free of geometry so that
// every row of the rule table in docs/decomposition.md is tested on hand-made cases:
// - classify_edge: the type of a Voronoi edge from its governors and their relations, and
//   the targets it is projected onto (faces, shared model edges, edge governors);
// - treat_vertex: one projection point per governor face at a Voronoi vertex, [1] edges
//   to be handled as [1s], and the closing rectangles v, pi_a(v), pi_ab(v), pi_b(v).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "model/brep_model.h"

namespace vorohex::decompose::detail {

using model::EntityKind;
using model::EntityRef;

// The relations between model entities that the rules read (the BRepModel in production,
// a table in tests).
class Relations {
 public:
  virtual ~Relations() = default;
  virtual bool unconnected(EntityRef a, EntityRef b) const = 0;
  // The model edge bounding both faces (the first one if several).
  virtual std::optional<EntityRef> shared_edge(EntityRef face_a, EntityRef face_b) const = 0;
  // Whether model edge `edge` bounds `face`.
  virtual bool bounds(EntityRef edge, EntityRef face) const = 0;
  // Whether all the entities touch one common model vertex.
  virtual bool common_vertex(const std::vector<EntityRef>& entities) const = 0;
  // Interior dihedral angle of the solid across a model edge, radians.
  virtual double dihedral(EntityRef edge) const = 0;
};

// Relations read from a BRepModel.
class ModelRelations : public Relations {
 public:
  explicit ModelRelations(const model::BRepModel& model) : model_(model) {}
  bool unconnected(EntityRef a, EntityRef b) const override;
  std::optional<EntityRef> shared_edge(EntityRef face_a, EntityRef face_b) const override;
  bool bounds(EntityRef edge, EntityRef face) const override;
  bool common_vertex(const std::vector<EntityRef>& entities) const override;
  double dihedral(EntityRef edge) const override;

 private:
  const model::BRepModel& model_;
};

enum class EdgeType {
  none,        // of no interest (bounds no f_s face)
  t0,          // [0] three faces, no pair shares an edge
  t1,          // [1] one pair shares an edge (not sharp)
  t1s,         // [1s] the same with a sharp angle along the shared edge
  t2,          // [2] two pairs share edges
  t3,          // [3] three pairs share edges (no common vertex)
  t1e,         // [1e] two faces and an edge governor bounding one of them
  t0e,         // [0e] two faces and a vertex or edge governor bounding neither
  tc,          // [C] the governors share a model vertex
  degenerate,  // more than three governors (or other mixes), per-governor rule
};
const char* edge_type_name(EdgeType t);  // "[0]", "[1s]", "[C]", "none", "degenerate"

// Where an edge (or a vertex) is projected for some of its governor faces: onto a face
// itself, onto the model edge two faces share ([1]), or onto an edge governor that bounds
// the face ([1e]). `faces` are the governor faces the target stands for.
struct Target {
  EntityRef entity;
  std::vector<EntityRef> faces;
  friend bool operator==(const Target& a, const Target& b) {
    return a.entity == b.entity && a.faces == b.faces;
  }
};

struct EdgeClass {
  EdgeType type = EdgeType::none;
  bool interest = false;        // bounds an f_s face (two unconnected face governors)
  std::vector<Target> targets;  // empty: not projected
};

// `sharp_angle`: radians; a shared model edge whose interior dihedral angle is below it
// makes a [1] edge a [1s] edge. `force_sharp`: face pairs to treat as sharp (set by the
// vertex treatment when a [1] projection conflicts with a face projection).
EdgeClass classify_edge(const std::vector<EntityRef>& governors, const Relations& rel,
                        double sharp_angle,
                        const std::vector<std::pair<EntityRef, EntityRef>>& force_sharp = {});

// One incident edge as the vertex treatment sees it.
struct IncidentEdge {
  std::vector<EntityRef> governors;
  EdgeClass cls;
};

struct Rectangle {
  EntityRef a, b;  // faces sharing a model edge: v, P_a, pi_ab(v), P_b
  EntityRef edge;  // their shared model edge
  friend bool operator==(const Rectangle& x, const Rectangle& y) {
    return x.a == y.a && x.b == y.b;
  }
};

struct VertexTreatment {
  std::string row;  // the table row: sorted edge types, e.g. "[2,2,C,C]"
  // The single projection point of each governor face that receives one: the entity the
  // vertex is projected onto for it (the face, a shared model edge, or an edge governor).
  std::vector<std::pair<EntityRef, EntityRef>> points;  // (face, target entity)
  std::vector<Rectangle> rectangles;
  // Face pairs of [1] edges that must be projected as [1s] (conflicting projections).
  std::vector<std::pair<EntityRef, EntityRef>> sharpen;
  // Faces whose cut stays open at the vertex (no rule closes it): a gap to report.
  std::vector<EntityRef> open;
  // The target entity for face f, if it has a point.
  std::optional<EntityRef> point_of(EntityRef f) const;
};

// `governors`: the vertex's governors; `edges`: its incident Voronoi edges, classified.
VertexTreatment treat_vertex(const std::vector<EntityRef>& governors,
                             const std::vector<IncidentEdge>& edges, const Relations& rel);

}  // namespace vorohex::decompose::detail
