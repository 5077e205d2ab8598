// Local refinement of the grid mesher's core grid, all-hex and conforming: a 27-tree.
// Level by level, the caller chooses cells to refine; each is divided into 27 (its edges
// in thirds), and its neighbours become transition cells filled by fixed templates, so
// that every face between two hexahedra is shared whole (no hanging node). A cell's
// template follows from which of its corners are marked (the corners of refined cells):
// none (the cell), one (4 hexahedra), the two ends of an edge (11), the four corners of a
// face (22) or all eight (27 children, the next level's cells); any other set of marked
// corners is completed to the smallest that one of these fits (three corners of a face to
// the face, two faces' corners to all eight). A face or edge of a cell is therefore divided by its
// own marked corners alone, the same way from both sides. The refinement of one level
// stays inside the cells refined at the level before (corners on the border of that
// region are never marked), so a transition cell never meets a finer one.
// (Refinement by thirds with vertex-marked templates: Schneiders 1996, Ito, Shih & Soni
// 2009; the templates here are this project's own.)
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/geometry.h"
#include "grid/detail/grid_frame.h"

namespace vorohex::grid::detail {

// Integer coordinates of the refined grid's points: 6 * 3^max_level units per base cell
// along each axis (base cell (i, j, k) spans [i, i + 1] * unit on the first axis, ...).
using LatticePoint = std::array<std::int64_t, 3>;

struct LatticeHash {
  std::size_t operator()(const LatticePoint& p) const {
    std::size_t h = std::size_t(p[0]) * 0x9E3779B97F4A7C15ull;
    h ^= std::size_t(p[1]) + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2);
    h ^= std::size_t(p[2]) + 0x94D049BB133111EBull + (h << 6) + (h >> 2);
    return h;
  }
};

// A cell of one level: its lowest corner and its edge length, in lattice units.
struct LevelCell {
  LatticePoint origin{};
  std::int64_t extent = 0;
};

struct RefinedGrid {
  int max_level = 0;
  std::int64_t unit = 6;                           // lattice units per base cell: 6 * 3^max_level
  std::vector<LatticePoint> lattice;               // per node
  std::vector<core::Vec3> points;                  // per node, world coordinates
  std::vector<std::array<std::int32_t, 8>> hexes;  // VTK order, positive
  std::vector<std::int8_t> level;                  // per hexahedron: its cell's level
  std::array<std::size_t, 4> templates{};  // transition cells by marked corners: 1, 2, 4; refined
  bool budget_reached = false;             // a level was left unrefined: it would pass max_hexes
};

// Chooses, for the cells of level `level` (0: the base grid), which to refine (one entry
// per cell; nonzero: refine). Called for levels 0 .. max_level - 1, only while some cell
// is refined.
using RefineChoice = std::function<std::vector<char>(int level, const std::vector<LevelCell>&)>;

// The base grid of `frame` refined up to max_level times (0 <= max_level <= 6). A level
// whose refinement (after the closure) would make the grid pass max_hexes hexahedra is
// not refined (its cells stay whole).
RefinedGrid refine_grid(const GridFrame& frame, int max_level, const RefineChoice& choose,
                        std::size_t max_hexes = std::size_t(-1));

// World coordinates of a lattice point.
core::Vec3 lattice_point(const GridFrame& frame, std::int64_t unit, const LatticePoint& p);

}  // namespace vorohex::grid::detail
