// The all-hexahedral mesh every stage produces and consumes.
//
// Hexahedra use VTK's node order: 0-1-2-3 one quad, 4-5-6-7 the opposite quad with node
// i+4 above node i, both counter-clockwise seen from the side of 4-5-6-7 (so a unit cube
// with nodes (0,0,0) (1,0,0) (1,1,0) (0,1,0) (0,0,1) (1,0,1) (1,1,1) (0,1,1) is positive).
// Every node is classified on the model entity it lies on (dimension 0/1/2, 1-based
// MapShapes index) or is interior (dimension 3).
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/geometry.h"
#include "core/ids.h"

namespace vorohex::core {

struct NodeClass {
  std::int8_t dim = 3;  // 0 vertex, 1 edge, 2 face, 3 interior
  std::int32_t id = 0;  // MapShapes index of the entity (0 when interior)

  static NodeClass interior() { return {3, 0}; }
  static NodeClass on(VertexId v) { return {0, v.value()}; }
  static NodeClass on(EdgeId e) { return {1, e.value()}; }
  static NodeClass on(FaceId f) { return {2, f.value()}; }
  bool is_interior() const { return dim == 3; }
  friend bool operator==(NodeClass a, NodeClass b) { return a.dim == b.dim && a.id == b.id; }
};

using HexNodes = std::array<std::int32_t, 8>;  // node indices, VTK order
// The 12 mid-edge nodes of a second-order (20-node) hexahedron, VTK_QUADRATIC_HEXAHEDRON
// order: on corner edges 0-1 1-2 2-3 3-0, 4-5 5-6 6-7 7-4, 0-4 1-5 2-6 3-7 (kHexEdges).
using MidEdgeNodes = std::array<std::int32_t, 12>;

class HexMesh {
 public:
  void reserve(std::size_t nodes, std::size_t hexes);

  NodeId add_node(const Vec3& p, NodeClass c = NodeClass::interior());
  HexId add_hex(const HexNodes& nodes, std::int32_t sub_volume = 0);

  std::size_t num_nodes() const { return points_.size(); }
  std::size_t num_hexes() const { return hexes_.size(); }

  const Vec3& point(NodeId n) const { return points_[n.value()]; }
  void set_point(NodeId n, const Vec3& p) { points_[n.value()] = p; }
  NodeClass node_class(NodeId n) const { return classes_[n.value()]; }
  void set_node_class(NodeId n, NodeClass c) { classes_[n.value()] = c; }
  const HexNodes& hex(HexId h) const { return hexes_[h.value()]; }
  std::int32_t sub_volume(HexId h) const { return sub_volumes_[h.value()]; }

  // The eight corner points of a hexahedron, VTK order.
  std::array<Vec3, 8> corners(HexId h) const;

  // Bulk access for writers, readers and numeric kernels.
  const std::vector<Vec3>& points() const { return points_; }
  const std::vector<NodeClass>& node_classes() const { return classes_; }
  const std::vector<HexNodes>& hexes() const { return hexes_; }
  const std::vector<std::int32_t>& sub_volumes() const { return sub_volumes_; }

  // Second order: every hexahedron has 12 mid-edge nodes (nodes of the same node arrays,
  // classified like the others), set once all hexahedra exist. A first-order mesh has none.
  int order() const { return mid_edges_.empty() || hexes_.empty() ? 1 : 2; }
  const std::vector<MidEdgeNodes>& mid_edge_nodes() const { return mid_edges_; }
  // One entry per hexahedron (an empty vector makes the mesh first order again).
  void set_mid_edge_nodes(std::vector<MidEdgeNodes> mid) { mid_edges_ = std::move(mid); }

  // Appends another mesh (nodes are not merged); returns the node offset used. Both must
  // have the same order.
  std::size_t append(const HexMesh& other);

  BoundingBox bounding_box() const;

 private:
  std::vector<Vec3> points_;
  std::vector<NodeClass> classes_;
  std::vector<HexNodes> hexes_;
  std::vector<std::int32_t> sub_volumes_;
  std::vector<MidEdgeNodes> mid_edges_;  // empty, or one per hexahedron
};

// The six quadrilateral faces of a VTK hexahedron, as local node indices, each ordered
// so that its normal points out of the hexahedron.
extern const std::array<std::array<int, 4>, 6> kHexFaces;
// The twelve edges of a VTK hexahedron as corner pairs, in the order of MidEdgeNodes.
extern const std::array<std::array<int, 2>, 12> kHexEdges;

// The boundary quads of a hex mesh: hexahedron faces that belong to no other hexahedron,
// in hexahedron order, then face order.
struct BoundaryFace {
  std::int32_t hex = 0;  // 0-based hexahedron index
  std::int8_t face = 0;  // index into kHexFaces (outward normal)
};
std::vector<BoundaryFace> boundary_faces(const HexMesh& mesh);

// Per node: 1 if it is a corner of a boundary quad.
std::vector<char> boundary_nodes(const HexMesh& mesh);

}  // namespace vorohex::core
