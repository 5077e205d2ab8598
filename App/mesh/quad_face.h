// General all-quad meshing of one face (planar or curved, with holes) whose boundary nodes
// are given: the face is charted in 2-D (MeshDomain::face_chart), meshed there by
// detail::quad_mesh_2d (constrained Delaunay of every other boundary node plus a lattice,
// triangle pairs merged, cells split into quads, quality-guarded smoothing) and mapped back
// onto the surface. The given boundary nodes are kept exactly.
#pragma once

#include <array>
#include <vector>

#include "core/diagnostic.h"
#include "core/geometry.h"
#include "core/ids.h"
#include "core/mesh_domain.h"
#include "core/size_field.h"

namespace vorohex::mesh {

struct QuadFaceOptions {
  double size = 1.0;          // target quad edge length, model units (> 0)
  int smoothing_passes = 30;  // passes of each smoothing kind (>= 0)
  // Rings of quads laid along each loop without sharp corners (round holes) before the rest
  // is meshed, at most this many (>= 0; 0: none, the lattice reaches the loops).
  int ring_layers = 3;
  // Local sizes (model coordinates; null or uniform: `size` everywhere). Not owned.
  const core::SizeField* size_field = nullptr;
  void validate() const;  // throws std::invalid_argument naming the bad field
};

struct QuadFaceMesh {
  // The boundary nodes exactly as given (loop after loop), then the inner nodes.
  std::vector<core::Vec3> points;
  std::size_t num_boundary = 0;
  // Counter-clockwise seen from outside the solid (normal = the face's outward normal).
  std::vector<std::array<int, 4>> quads;
  double min_quality = 0, mean_quality = 0;  // 2-D quad scaled Jacobian in the chart
  bool ok = false;
  std::vector<core::Diagnostic> diagnostics;
};

// loops: the face's boundary as closed cycles of nodes (first node not repeated), in the
// order and orientation of MeshDomain::face_wires (outer first; face on the left seen from
// outside). Every loop must have an even number of nodes (segments), at least 6, or exactly
// 4 for a face without holes; this per-loop parity is what the mesher needs (an even total
// alone is not enough).
QuadFaceMesh quad_face(const core::MeshDomain& solid, core::FaceId face,
                       const std::vector<std::vector<core::Vec3>>& loops,
                       const QuadFaceOptions& options);

}  // namespace vorohex::mesh
