// Conforming quad meshes of a set of faces that share edges (the regions of a multisweep's
// arrangement, a revolve's meridian section): one interval assignment over all their
// edges, then each face mapped (one wire of four sides whose corners are near right angles:
// transfinite grid), else submapped (its corners turn by multiples of 90 degrees: lattice),
// else meshed by the general quad mesher (quad_face). Nodes on a shared edge or vertex are
// shared, so the faces' meshes conform by construction. A face whose mapped grid or lattice
// folds is meshed by quad_face instead (the assignment is solved again).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "core/geometry.h"
#include "core/hex_mesh.h"
#include "core/mesh_domain.h"
#include "core/progress.h"
#include "core/size_field.h"

namespace vorohex::mesh {

struct FaceSetOptions {
  double size = 1.0;                // target quad edge length, model units (> 0)
  int max_intervals = 100000;       // per edge (> 0)
  int smoothing_passes = 30;        // of faces meshed by quad_face (>= 0)
  double interval_time_limit = 20;  // seconds for the integer program (> 0)
  // Per edge id (entry 0 unused; 0 or missing: free): counts the edges must have.
  std::vector<int> fixed_counts;
  // Chains of edges whose counts must sum to a given count (a neighbour's edge that the
  // set's edges split: a multisweep's arrangement under a sub-volume's shared edge).
  struct FixedSum {
    std::vector<int> edges;  // edge ids
    int count = 0;           // >= 1
  };
  std::vector<FixedSum> fixed_sums;
  // Per edge id (entry 0 unused; empty or missing: free): the edge's nodes, first to last
  // vertex, as a neighbour placed them (the count is theirs, their positions are kept).
  std::vector<std::vector<core::Vec3>> given_edge_points;
  // Local sizes (null or uniform: `size` everywhere): edge counts, edge nodes and quad
  // faces follow them. Not owned.
  const core::SizeField* size_field = nullptr;
  void validate() const;  // throws std::invalid_argument naming the bad field
};

struct FaceSetMesh {
  std::vector<core::Vec3> points;
  // Per node: the entity of the face set it lies on (vertex, edge or face of `faces`).
  std::vector<core::NodeClass> on;
  // Per face id (entry 0 unused): its quads, counter-clockwise about the face's normal.
  std::vector<std::vector<std::array<int, 4>>> quads;
  std::vector<int> edge_counts;              // per edge id (entry 0 unused)
  std::vector<std::vector<int>> edge_nodes;  // per edge id: its nodes, first to last vertex
  std::vector<std::string> face_schemes;     // per face id: "map", "submap" or "quad"
  double min_quality = 1, mean_quality = 0;  // 2-D quad scaled Jacobian over all faces
  bool ok = false;
  std::vector<core::Diagnostic> diagnostics;
  std::size_t num_quads() const;
};

// `faces`: a domain whose faces are the set (e.g. an occ::Solid of a compound of faces, any
// shape); every face is meshed. Errors: intervals_infeasible, quad_face_failed, cancelled.
FaceSetMesh mesh_face_set(const core::MeshDomain& faces, const FaceSetOptions& options,
                          const core::Progress& progress = {});

}  // namespace vorohex::mesh
