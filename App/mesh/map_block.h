// Mapped (transfinite) meshing of a topological hexahedron: a solid of six faces with one
// wire of four edges each (planar or curved). Intervals come from the target size and are
// equal on the four parallel edges of each direction; edge nodes are placed by arc length,
// face nodes by 2-D transfinite interpolation (projected onto curved faces), inner nodes by
// 3-D transfinite interpolation.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"
#include "core/mesh_domain.h"
#include "core/progress.h"
#include "core/size_field.h"

namespace vorohex::mesh {

struct MapBlockOptions {
  double size = 1.0;           // target edge length, model units (> 0)
  int max_intervals = 100000;  // per direction; more is refused (> 0)
  // Given intervals per edge id (entry 0 unused), e.g. from assign_intervals, instead of
  // the size: the four parallel edges of each direction must agree (else an error).
  std::vector<int> edge_intervals;
  // Local sizes (null or uniform: `size` everywhere): each direction takes the finest count
  // its four edges ask for, and the edge nodes follow the field. Not owned.
  const core::SizeField* size_field = nullptr;
  // Per edge id: nodes a neighbouring sub-volume already placed on it (first to last
  // vertex), taken instead of the edge's own spacing when their number fits its count.
  std::vector<std::vector<core::Vec3>> edge_nodes;
  void validate() const;  // throws std::invalid_argument naming the bad field
};

struct Applicability {
  bool ok = false;
  std::string reason;  // why not, naming the entities ("Face3 has 5 edges")
};

// The block structure of a solid that map_block accepts.
Applicability map_block_applicable(const core::MeshDomain& solid);

// The block's edges by direction: three groups of four parallel edges (empty groups when
// the solid is not a block). What an interval assignment must keep equal.
std::array<std::vector<core::EdgeId>, 3> map_block_edge_groups(const core::MeshDomain& solid);

// Intervals per block direction and the node and hex counts compute() will produce.
struct MapBlockEstimate {
  std::array<int, 3> intervals{};
  std::size_t nodes = 0, hexes = 0;
};
MapBlockEstimate map_block_evaluate(const core::MeshDomain& solid, const MapBlockOptions& options);

struct MapBlockResult {
  core::HexMesh mesh;
  std::array<int, 3> intervals{};
  bool ok = false;
  std::vector<core::Diagnostic> diagnostics;
};

MapBlockResult map_block(const core::MeshDomain& solid, const MapBlockOptions& options,
                         const core::Progress& progress = {});

}  // namespace vorohex::mesh
