// The embedded Voronoi graph of a solid (paper §2-3), built by space subdivision (Etzion &
// Rappoport): an adaptive octree whose cells keep the boundary entities that can be nearest
// to some point of the cell; the symbolic structure (which governor sets meet) comes from
// the finest cells, and Voronoi vertices and edges are then placed exactly from their
// governors and checked.
//
// Conventions
// - Governors are model entities (faces, edges, vertices). A point inside the solid belongs
//   to the entity whose relative interior holds its nearest boundary point; only faces,
//   concave edges and concave vertices own interior regions. Curved faces and edges are
//   linearised (ModelOptions) and every linear piece answers with its model entity, so
//   there are no Voronoi elements between facets of one face (the paper's uniting).
// - Approximate graph: Voronoi elements within about eps of each other are merged into one
//   node that keeps all their governors (a degenerate vertex such as a cube's centre).
// - One face node per pair of governors (disconnected faces with the same two governors
//   are one node); vertices and edges are separate nodes per connected piece.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "core/geometry.h"
#include "model/brep_model.h"
#include "occ/solid.h"

namespace vorohex::voronoi {

using core::Vec3;
using model::EntityRef;

struct VoronoiOptions {
  // Resolution of the subdivision: the finest cells are at most eps wide, and Voronoi
  // elements closer than about eps are merged. Relative to the bounding-box diagonal.
  double eps = 0.01;
  // Accuracy of the embedding: a placed vertex or polyline point is equidistant from its
  // governors within delta and no other entity is nearer by more than delta. Relative to
  // the bounding-box diagonal.
  double delta = 0.001;
  // Maximum octree depth (the root cell encloses the solid); caps the cost when eps is
  // small. Dimensionless, 1..12.
  int max_depth = 9;
  // Chord tolerance of the linearisation of curved faces and edges, relative to the
  // bounding-box diagonal (ModelOptions::linear_tolerance).
  double linear_tolerance = 0.005;
  // Threads for the subdivision (independent subtrees); 0: one per hardware thread. The
  // result does not depend on it.
  int threads = 0;
  // Empty if valid, else the reason.
  std::string validate() const;
};

enum class ElementKind { face, edge, vertex };
const char* element_kind_name(ElementKind k);

struct VoronoiElement {
  ElementKind kind = ElementKind::face;
  std::vector<EntityRef> governors;  // sorted; faces first, then edges, then vertices
  // Vertex: its position. Edge: its middle. Face: a point of the face.
  Vec3 point{0, 0, 0};
  double radius = 0;           // distance from `point` to the governors
  std::vector<Vec3> polyline;  // edges: from one end to the other
  bool verified = false;       // point (and polyline) checked to delta
  bool fs = false;             // face governed by two unconnected model faces
  std::vector<int> incident;   // indices of incident elements (sorted)
};

struct VoronoiGraph {
  std::vector<VoronoiElement> elements;

  std::vector<int> of_kind(ElementKind k) const;
  // The f_s faces: Voronoi faces governed by two unconnected faces (paper §3).
  std::vector<int> fs_faces() const;
  // The Voronoi edges bounding a Voronoi face (its incident edges).
  std::vector<int> bounding_edges(int face) const;
  // The vertices at the ends of a Voronoi edge (0, 1 or 2; ends on the solid's boundary
  // have no vertex).
  std::vector<int> edge_vertices(int edge) const;
  // Elements whose governors are exactly `governors` (any order).
  std::vector<int> find(std::vector<EntityRef> governors) const;
};

// Point location in the subdivision: the entity whose Voronoi region holds a point.
class RegionLocator {
 public:
  virtual ~RegionLocator() = default;
  // The entity whose region holds p (a point inside the solid); {face, id 0} when p is
  // outside the subdivided box or found outside the solid.
  virtual EntityRef region(const Vec3& p) const = 0;
};

struct VoronoiStats {
  long long cells = 0;  // octree cells visited
  long long leaves = 0;
  long long finest_cells = 0;  // cells at the finest level holding 3+ candidates
  long long distance_evaluations = 0;
  int finest_level = 0;
  double seconds = 0;        // wall time of the whole computation
  double model_seconds = 0;  // part of it spent building the BRepModel
};

enum class VoronoiStatus { ok, partial, failed };

struct VoronoiResult {
  VoronoiGraph graph;
  VoronoiStatus status = VoronoiStatus::failed;
  std::vector<core::Diagnostic> diagnostics;  // warnings name unverified elements
  VoronoiStats stats;
  std::shared_ptr<const model::BRepModel> model;  // the model the governors refer to
  std::shared_ptr<const RegionLocator> locator;   // the subdivision, for point queries
  bool ok() const { return status != VoronoiStatus::failed; }
};

// Builds the model (linearised to options.linear_tolerance) and its Voronoi graph.
VoronoiResult compute_voronoi_graph(const occ::Solid& solid, const VoronoiOptions& options = {});
// The graph of an already built model (options.linear_tolerance is not used).
VoronoiResult compute_voronoi_graph(std::shared_ptr<const model::BRepModel> model,
                                    const VoronoiOptions& options = {});

}  // namespace vorohex::voronoi
