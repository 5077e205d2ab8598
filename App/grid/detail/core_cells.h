// The core of the grid mesher: grid cells well inside the solid. A cell is in the core
// when its eight corners are inside the solid (OCCT's classifier, exact) and farther than
// margin * size from its boundary; the core is then made a manifold (its boundary a closed
// surface without pinched edges or vertices) and reduced to its largest face-connected part.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include "grid/detail/grid_frame.h"
#include "occ/solid.h"
#include "occ/tessellate.h"

namespace vorohex::grid::detail {

struct CoreCells {
  std::array<int, 3> cells{};  // per axis
  std::vector<char> in_core;   // per cell, index i + cells[0] * (j + cells[1] * k)
  std::size_t core = 0;        // cells in the core
  std::size_t removed_for_manifold = 0, removed_components = 0;
  std::size_t classifier_calls = 0;

  std::size_t index(int i, int j, int k) const {
    return std::size_t(i) + std::size_t(cells[0]) * (std::size_t(j) + std::size_t(cells[1]) * k);
  }
  bool at(int i, int j, int k) const {
    if (i < 0 || j < 0 || k < 0 || i >= cells[0] || j >= cells[1] || k >= cells[2]) return false;
    return in_core[index(i, j, k)] != 0;
  }
};

// Distance from p to the triangle abc.
double point_triangle_distance(const core::Vec3& p, const core::Vec3& a, const core::Vec3& b,
                               const core::Vec3& c);

struct UnionFind {
  std::vector<std::size_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) {
    for (std::size_t i = 0; i < n; ++i) parent[i] = i;
  }
  std::size_t find(std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::size_t a, std::size_t b) { parent[find(a)] = find(b); }
};

// Inside the solid, for the points farther than `far` from its boundary (dist: per point):
// the sets `uf` joins (points joined by segments that cannot cross the boundary: the sum
// of their distances exceeds the length) share one answer, the majority of up to three of
// their farthest points classified by OCCT (`point(i)`: point i; `calls` counts them).
std::vector<char> vote_inside(const occ::Solid& solid, UnionFind& uf,
                              const std::vector<double>& dist, double far,
                              const std::function<core::Vec3(std::size_t)>& point, double tolerance,
                              std::size_t& calls);

// Unsigned distance of each grid node to the tessellated boundary, capped at `cap`
// (nodes farther away get `cap`). Node index i + n0 * (j + n1 * k).
std::vector<double> node_distances(const GridFrame& frame, const occ::Tessellation& t, double cap);

CoreCells core_cells(const GridFrame& frame, const occ::Solid& solid, const occ::Tessellation& t,
                     double size, double margin, double deflection);

}  // namespace vorohex::grid::detail
