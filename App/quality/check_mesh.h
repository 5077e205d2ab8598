// Validity of a hex mesh, with or without its CAD solid: the invariants every VoroHex
// result must satisfy and that `vorohex check` reports for any tool's mesh.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"
#include "occ/solid.h"
#include "quality/quality_stats.h"

namespace vorohex::quality {

struct CheckOptions {
  // Volume: |mesh - CAD| must be <= volume_rel_tol * CAD volume + chord allowance, where the
  // chord allowance is the sum over boundary quads of area * distance of the quad centre
  // from the CAD boundary (zero for planar solids, so planar meshes must match exactly).
  // Quads with a node off the CAD (see distance_rel_tol) are no chords and get none.
  double volume_rel_tol = 1e-9;
  // Boundary nodes must lie within this distance of the CAD boundary, relative to the
  // CAD bounding-box diagonal (or within the CAD's own OCCT tolerance, if larger).
  double distance_rel_tol = 1e-6;
  void validate() const;  // throws std::invalid_argument naming the bad field
};

// One of the hexahedra of lowest scaled Jacobian: where it is and which CAD entities its
// nodes lie on (so a user can tell a sharp edge of the part from a poor mesh).
struct WorstHex {
  std::size_t hex = 0;  // index in the mesh (0-based)
  double scaled_jacobian = 0;
  core::Vec3 centre{0, 0, 0};         // mean of its corner nodes
  std::vector<std::string> entities;  // "Vertex3", "Edge9", "Face2" (vertices, edges, faces)
};

struct CheckReport {
  bool valid = false;
  std::size_t nodes = 0, hexes = 0;
  QualityStats scaled_jacobian;         // Verdict scaled Jacobian statistics
  std::size_t non_positive = 0;         // hexes with scaled Jacobian <= 0
  std::size_t degenerate = 0;           // hexes with 0 < scaled Jacobian < 1e-6 (flat)
  std::size_t non_positive_gauss = 0;   // 20-node hexes with det J <= 0 at a Gauss point
  int order = 1;                        // 1: 8-node hexahedra, 2: 20-node
  std::size_t interior_quads = 0;       // quads shared by exactly two hexes
  std::size_t boundary_quads = 0;       // quads of exactly one hex
  std::size_t non_manifold_quads = 0;   // quads shared by more than two hexes
  std::size_t folded_quads = 0;         // quads shared by two hexes on the same side (overlap)
  std::size_t open_boundary_edges = 0;  // boundary edges not in exactly two boundary quads
  std::size_t unused_nodes = 0;
  bool has_cad = false;
  double mesh_volume = 0, cad_volume = 0;
  double volume_rel_error = 0;                // |mesh - CAD| / CAD
  double volume_allowance = 0;                // the absolute tolerance applied (see CheckOptions)
  double max_boundary_distance = 0;           // absolute, model units
  double max_boundary_distance_rel = 0;       // relative to the CAD diagonal
  std::vector<core::Diagnostic> diagnostics;  // one per violated invariant
  std::vector<WorstHex> worst;                // the (at most) three lowest, worst first
};

// cad may be null: then only the mesh-intrinsic invariants are checked. Nodes classified on
// an entity are measured against that entity, other boundary nodes against the nearest face.
// If scaled_jacobian is given, it receives the per-hex values the check computed (so callers
// that also need them, e.g. for writing, do not compute them twice).
CheckReport check_mesh(const core::HexMesh& mesh, const occ::Solid* cad,
                       const CheckOptions& options = {},
                       std::vector<double>* scaled_jacobian = nullptr);

// The sum of the hexahedra's volumes (as their corners give them: check_mesh's mesh_volume).
double mesh_volume(const core::HexMesh& mesh);

// The mesh's topology only (what moving nodes cannot change): node indices, quads shared by
// more than two hexahedra, a closed boundary (and, as check_mesh counts them, overlapping
// quads). No element quality, no CAD; `valid` stays false, the counts and errors are set.
CheckReport check_topology(const core::HexMesh& mesh);

}  // namespace vorohex::quality
