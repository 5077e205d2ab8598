// Named groups per CAD entity, as FEA decks refer to them: for every model face, edge and
// vertex ("Face7", "Edge3", "Vertex1", the ids of the report and of FreeCAD) the nodes on
// it (its boundary included), and for faces also the element faces on it. Built from the
// node classification every mesh carries, with the solid's topology for the closure.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/hex_mesh.h"
#include "core/mesh_domain.h"

namespace vorohex::io {

struct GroupFace {
  std::int32_t hex = 0;  // 0-based hexahedron index
  std::int8_t face = 0;  // index into core::kHexFaces (outward normal)
};

struct GroupEdge {
  std::int32_t hex = 0;  // 0-based hexahedron index
  std::int8_t edge = 0;  // index into core::kHexEdges
};

struct NamedGroup {
  std::string name;                 // "Face7", "Edge3", "Vertex1"
  int dim = 2;                      // 0 vertex, 1 edge, 2 face
  std::int32_t id = 0;              // the entity's MapShapes index (1-based)
  std::vector<std::int32_t> nodes;  // 0-based, ascending: nodes on the entity or its boundary
  std::vector<GroupFace> faces;     // faces only: the boundary quads on the face
  std::vector<GroupEdge> edges;     // edges only: the mesh edges along it (each once)
};

// One group per face, edge and vertex of `domain` that has at least one node, faces first,
// each kind by id. A boundary quad belongs to the face all four of its corners lie on (the
// nearest to its centre if several); a mesh edge of a boundary quad to the model edge both
// its ends lie on.
std::vector<NamedGroup> named_groups(const core::HexMesh& mesh, const core::MeshDomain& domain);

// Name of an entity as in FreeCAD: "Vertex1", "Edge3", "Face7".
std::string entity_name(int dim, std::int32_t id);

}  // namespace vorohex::io
