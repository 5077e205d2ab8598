// The grid mesher's core on a locally refined grid (grid/detail/adaptive_core.h, issue 23
// item 1): walls thinner than the cells are refined until a core fits in them.
#include "grid/detail/adaptive_core.h"

#include <gtest/gtest.h>

#include "fixtures/machined.h"
#include "grid/grid_mesh.h"
#include "occ/primitives.h"
#include "quality/check_mesh.h"

namespace vorohex {
namespace {

occ::Tessellation tessellation(const occ::Solid& s, double deflection) {
  occ::TessellationOptions o;
  o.linear_deflection = deflection;
  return occ::tessellate(s, o);
}

std::vector<core::Vec3> points(const occ::Tessellation& t) {
  std::vector<core::Vec3> p;
  for (const auto& f : t.faces) p.insert(p.end(), f.nodes.begin(), f.nodes.end());
  return p;
}

TEST(AdaptiveCore, APlateThinnerThanTheCellsGetsACoreOfFinerCells) {
  const occ::Solid plate = occ::make_box(10, 10, 0.8);
  const double size = 2;
  const occ::Tessellation t = tessellation(plate, 0.01);
  const grid::detail::GridFrame f = grid::detail::grid_frame(plate, points(t), size);
  grid::detail::AdaptiveCoreOptions o;
  o.size = size;
  o.deflection = 0.01;
  const grid::detail::AdaptiveCore a = grid::detail::adaptive_core(f, plate, t, o);
  EXPECT_EQ(a.levels_used, 2);
  EXPECT_GT(a.core.size(), 0u);
  EXPECT_GT(a.core_volume, 0.3 * 80);
  EXPECT_EQ(a.removed_components, 0u);
  EXPECT_FALSE(a.budget_reached);
}

TEST(AdaptiveCore, RefinementStopsAtTheBudget) {
  const occ::Solid plate = occ::make_box(10, 10, 0.8);
  const occ::Tessellation t = tessellation(plate, 0.01);
  const grid::detail::GridFrame f = grid::detail::grid_frame(plate, points(t), 2);
  grid::detail::AdaptiveCoreOptions o;
  o.size = 2;
  o.deflection = 0.01;
  o.max_cells = 2000;  // level 1 (25 cells -> 675) fits, level 2 (about 18000) does not
  const grid::detail::AdaptiveCore a = grid::detail::adaptive_core(f, plate, t, o);
  EXPECT_TRUE(a.budget_reached);
  EXPECT_LE(a.grid.hexes.size(), 2000u);
  EXPECT_LE(a.levels_used, 1);
}

TEST(GridMesh, APlateThinnerThanTheSizeIsRefinedLocallyAndValid) {
  // A 4 x 4 plate 0.4 thick with a 1 x 1 x 2 block standing on it, at size 1: the uniform
  // core has no cell in the plate, even at size 0.25 (two halvings); refined by thirds
  // near it, the core reaches into it and the mesh is valid.
  const occ::Solid part =
      testing::fuse(occ::make_box(4, 4, 0.4), occ::make_box(1, 1, 2, core::Vec3(1.5, 1.5, 0.4)));
  grid::GridOptions o;
  o.size = 1;
  const grid::GridResult r = grid::grid_mesh(part, o);
  ASSERT_TRUE(r.ok);
  EXPECT_GE(r.stats.local_levels, 1);
  bool said = false;
  for (const core::Diagnostic& d : r.diagnostics) said = said || d.code == "grid_refined_locally";
  EXPECT_TRUE(said);
  const quality::CheckReport c = quality::check_mesh(r.mesh, &part);
  EXPECT_TRUE(c.valid) << (c.diagnostics.empty() ? "" : c.diagnostics.front().message);
  EXPECT_GT(c.scaled_jacobian.min, 0.2);
  // Without local refinement (max_levels 0) the grid halves its size, and its core stays
  // out of the plate.
  o.max_levels = 0;
  const grid::GridResult u = grid::grid_mesh(part, o);
  EXPECT_EQ(u.stats.local_levels, 0);
  EXPECT_LT(u.stats.core_hexes, r.stats.core_hexes);
}

}  // namespace
}  // namespace vorohex
