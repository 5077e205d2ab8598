// Local refinement of the grid by thirds (grid/detail/refine.h, issue 23 item 1): every
// refinement pattern gives a conforming all-hex mesh of the box, no element inverted.
#include "grid/detail/refine.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/hex_mesh.h"
#include "quality/check_mesh.h"

namespace vorohex {
namespace {

using grid::detail::GridFrame;
using grid::detail::LevelCell;
using grid::detail::RefinedGrid;

GridFrame box_frame(const std::array<std::vector<double>, 3>& lines) {
  GridFrame f;
  f.axes = {core::Vec3(1, 0, 0), core::Vec3(0, 1, 0), core::Vec3(0, 0, 1)};
  f.lines = lines;
  f.how = "test";
  return f;
}

core::HexMesh to_mesh(const RefinedGrid& g) {
  core::HexMesh m;
  for (const core::Vec3& p : g.points) m.add_node(p);
  for (const auto& h : g.hexes) m.add_hex(h);
  return m;
}

// The box is filled exactly once, conforming, closed, no element flat or inverted.
void expect_valid(const RefinedGrid& g, double volume, const std::string& what,
                  double min_sj = 0.3) {
  const core::HexMesh m = to_mesh(g);
  const quality::CheckReport c = quality::check_mesh(m, nullptr);
  EXPECT_EQ(c.non_positive, 0u) << what;
  EXPECT_EQ(c.degenerate, 0u) << what;
  EXPECT_EQ(c.non_manifold_quads, 0u) << what;
  EXPECT_EQ(c.folded_quads, 0u) << what;
  EXPECT_EQ(c.open_boundary_edges, 0u) << what;
  EXPECT_EQ(c.unused_nodes, 0u) << what;
  EXPECT_NEAR(c.mesh_volume, volume, 1e-9 * volume) << what;
  // Templates are distorted but not badly: the worst corner of any of them (0.316 in cubic
  // cells; less in cells stretched by an uneven grid).
  EXPECT_GT(c.scaled_jacobian.min, min_sj) << what;
}

// Refines the cells of level `level` that `pick` names.
grid::detail::RefineChoice refine_where(std::function<bool(int, const LevelCell&)> pick) {
  return [pick](int level, const std::vector<LevelCell>& cells) {
    std::vector<char> out(cells.size());
    for (std::size_t c = 0; c < cells.size(); ++c) out[c] = pick(level, cells[c]);
    return out;
  };
}

TEST(Refine, TheCentreCellOfThreeByThreeGivesEveryTemplate) {
  const GridFrame f = box_frame({{{0, 1, 2, 3}, {0, 1, 2, 3}, {0, 1, 2, 3}}});
  const RefinedGrid g = grid::detail::refine_grid(
      f, 1, refine_where([](int, const LevelCell& c) {
        return c.origin[0] == c.extent && c.origin[1] == c.extent && c.origin[2] == c.extent;
      }));
  // Its 6 face neighbours share 4 marked corners, its 12 edge neighbours 2, its 8 corner
  // neighbours 1.
  EXPECT_EQ(g.templates, (std::array<std::size_t, 4>{8, 12, 6, 1}));
  EXPECT_EQ(g.hexes.size(), std::size_t(8 * 4 + 12 * 11 + 6 * 22 + 27));
  expect_valid(g, 27, "centre cell");
}

TEST(Refine, MarkedCornersThatFitNoTemplateRefineTheirCell) {
  // Two cells touching at one edge: the cells around that edge see both, so the closure
  // refines more; the result stays conforming.
  const GridFrame f = box_frame({{{0, 1, 2, 3, 4}, {0, 1, 2, 3}, {0, 1, 2}}});
  const RefinedGrid g = grid::detail::refine_grid(
      f, 1, refine_where([](int, const LevelCell& c) {
        const std::int64_t i = c.origin[0] / c.extent, j = c.origin[1] / c.extent,
                           k = c.origin[2] / c.extent;
        return (i == 1 && j == 1 && k == 0) || (i == 2 && j == 0 && k == 1);
      }));
  EXPECT_GT(g.templates[3], 2u);
  expect_valid(g, 24, "diagonal pair");
}

TEST(Refine, MarkedCornersAreCompletedToTheSmallestTemplateThatFits) {
  // Cells (0, 0, 0) and (2, 2, 0) refined; (1, 1, 0) between them sees two opposite edges
  // marked and is refined whole; the cell above it, (1, 1, 1), then has the four corners of
  // its lower face marked (two of them by the first two cells alone, diagonal on that face).
  // Completed to that face, not to the whole cell, it is one face template (22 hexahedra),
  // not 27 children.
  const GridFrame f = box_frame({{{0, 1, 2, 3}, {0, 1, 2, 3}, {0, 1, 2}}});
  const RefinedGrid g = grid::detail::refine_grid(f, 1, refine_where([](int, const LevelCell& c) {
                                                    const std::int64_t i = c.origin[0] / c.extent,
                                                                       j = c.origin[1] / c.extent,
                                                                       k = c.origin[2] / c.extent;
                                                    return k == 0 && i == j && i != 1;
                                                  }));
  std::size_t inside = 0;
  for (const auto& h : g.hexes) {
    bool in = true;
    for (std::int32_t n : h)
      for (int a = 0; a < 3; ++a)
        in = in && g.points[n][a] >= 1 - 1e-9 && g.points[n][a] <= 2 + 1e-9;
    inside += in;
  }
  EXPECT_EQ(inside, 22u);
  expect_valid(g, 18, "completed to a face");
}

TEST(Refine, BallsRefinedOverTwoLevelsStayConformingOnAnUnevenGrid) {
  // As a sizing field asks: the cells near a random point refined once, those nearer
  // refined again.
  std::mt19937 rng(7);
  std::array<std::vector<double>, 3> lines;
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i <= 6; ++i) lines[a].push_back(i + 0.3 * std::sin(3.0 * i + a));
  const GridFrame f = box_frame(lines);
  double volume = 1;
  for (int a = 0; a < 3; ++a) volume *= lines[a].back() - lines[a].front();
  std::uniform_real_distribution<double> u(0, 6);
  int twice = 0;
  for (int trial = 0; trial < 10; ++trial) {
    const core::Vec3 centre(u(rng), u(rng), u(rng));
    const double radius = 0.8 + 0.25 * trial;
    const RefinedGrid g =
        grid::detail::refine_grid(f, 2, [&](int level, const std::vector<LevelCell>& cells) {
          std::vector<char> out(cells.size());
          for (std::size_t c = 0; c < cells.size(); ++c) {
            const double unit = 54;  // 6 * 3^2 lattice units per base cell
            const core::Vec3 mid((cells[c].origin[0] + 0.5 * cells[c].extent) / unit,
                                 (cells[c].origin[1] + 0.5 * cells[c].extent) / unit,
                                 (cells[c].origin[2] + 0.5 * cells[c].extent) / unit);
            out[c] = (mid - centre).norm() < radius / (1 + level);
          }
          return out;
        });
    const std::string what = "trial " + std::to_string(trial);
    EXPECT_EQ(g.unit, 54) << what;
    // Base cells up to 1.9 times longer one way than another: templates down to 0.10.
    expect_valid(g, volume, what, 0.08);
    // Transitions, and hexahedra of all three levels.
    std::array<std::size_t, 3> per_level{};
    for (auto l : g.level) ++per_level[l];
    EXPECT_GT(g.templates[0] + g.templates[1] + g.templates[2], 0u) << what;
    EXPECT_GT(per_level[0], 0u) << what;
    twice += per_level[2] > 0;
  }
  // Level 1's choice stays off the border of level 0's refined cells: small balls near
  // that border are not refined twice, the others are.
  EXPECT_GE(twice, 5);
}

TEST(Refine, NothingChosenIsTheBaseGrid) {
  const GridFrame f = box_frame({{{0, 1, 2}, {0, 1}, {0, 2, 3}}});
  const RefinedGrid g =
      grid::detail::refine_grid(f, 3, refine_where([](int, const LevelCell&) { return false; }));
  EXPECT_EQ(g.hexes.size(), 4u);
  EXPECT_EQ(g.points.size(), std::size_t(3 * 2 * 3));
  expect_valid(g, 6, "none");
  EXPECT_THROW(
      grid::detail::refine_grid(f, 7, refine_where([](int, const LevelCell&) { return false; })),
      std::invalid_argument);
}

}  // namespace
}  // namespace vorohex
