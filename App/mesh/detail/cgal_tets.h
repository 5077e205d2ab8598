// The tetrahedral mesh under the fallback: CGAL's Delaunay refinement (Mesh_3) of the
// volume bounded by a closed triangulated surface, with polylines kept as features, as
// plain arrays (so it can cross a process boundary: CGAL 5.5's global optimiser can crash
// on features, and tet_split runs this in a child process, see core/isolated_call.h).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/hex_mesh.h"

namespace vorohex::mesh::detail {

// A closed triangulated surface; patch[i] is the model face triangle i approximates.
struct TetSurface {
  std::vector<core::Vec3> points;
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> patch;
};

enum class TetOptimiser {
  odt,      // ODT smoothing then sliver perturbation: the best tetrahedra
  perturb,  // sliver perturbation only: used when ODT crashed
};

struct TetRequest {
  TetSurface surface;
  std::vector<std::vector<core::Vec3>> features;  // polylines the mesh keeps as edges
  double size = 1.0;                              // tetrahedron edge length (> 0)
  TetOptimiser optimiser = TetOptimiser::odt;
};

struct Tetrahedra {
  std::vector<core::Vec3> points;
  std::vector<int> dimension;  // of the complex entity each point lies on: 0 corner ... 3
  std::vector<std::array<int, 4>> tets;
  std::vector<std::array<int, 2>> feature_edges;  // sorted node pairs
  std::vector<std::array<int, 3>> facets;         // boundary triangles, sorted node triples
  std::vector<int> facet_patch;                   // their surface patch (model face)
  int filled = 0;  // cells added to close gaps at pinched edges (in `tets`, not in `facets`)
};

// Builds the polyhedron and meshes it. Throws std::runtime_error naming what failed (a
// surface that is not a closed manifold, an exception from CGAL).
Tetrahedra mesh_tetrahedra(const TetRequest& request);

// A byte form of Tetrahedra and its inverse (false on bytes that do not parse).
std::string to_bytes(const Tetrahedra& t);
bool from_bytes(const std::string& bytes, Tetrahedra& t);

}  // namespace vorohex::mesh::detail
