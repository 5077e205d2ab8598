// The grid mesher: invariants on every result (all scaled Jacobians > 0, conforming, closed
// boundary, volume and boundary nodes on the CAD, via quality::check_mesh) and its parts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "fixtures/diagnostics.h"
#include "fixtures/machined.h"
#include "fixtures/solids.h"
#include "grid/detail/core_cells.h"
#include "grid/detail/grid_frame.h"
#include "grid/detail/pillow.h"
#include "grid/grid_mesh.h"
#include "occ/primitives.h"
#include "occ/shape_io.h"
#include "occ/split_solid.h"
#include "occ/tessellate.h"
#include "pipeline/generate_mesh.h"
#include "quality/check_mesh.h"
#include "quality/scaled_jacobian.h"

namespace vorohex {
namespace {

using core::Vec3;

struct Named {
  std::string name;
  occ::Solid solid;
  double size;
};

std::vector<core::Vec3> boundary_points(const occ::Solid& s) {
  occ::TessellationOptions o;
  o.linear_deflection = 0.01 * s.diagonal();
  const occ::Tessellation t = occ::tessellate(s, o);
  std::vector<Vec3> p;
  for (const auto& f : t.faces) p.insert(p.end(), f.nodes.begin(), f.nodes.end());
  return p;
}

// Every result must pass the project's validity check: positive scaled Jacobians,
// conforming, closed, volume and boundary nodes on the CAD. Its one warning allowed here is
// boundary_across_edges: the pillow layer's quads still cut across sharp edges where the
// feature capture did not follow them or untangling moved their nodes off them (n06 17
// quads, HexMe's industrial parts over a hundred: issue 23's "each boundary quad on exactly
// one model face" is not met yet); the check names them since it looks for them.
void expect_valid(const occ::Solid& solid, const grid::GridResult& r) {
  ASSERT_TRUE(r.ok);
  const quality::CheckReport c = quality::check_mesh(r.mesh, &solid);
  for (const core::Diagnostic& d : c.diagnostics)
    if (d.code != "boundary_across_edges") ADD_FAILURE() << core::format(d);
  EXPECT_TRUE(c.valid);
  EXPECT_EQ(c.non_positive, 0u);
  EXPECT_EQ(c.non_manifold_quads, 0u);
  EXPECT_EQ(c.folded_quads, 0u);
  EXPECT_EQ(c.open_boundary_edges, 0u);
  EXPECT_GT(c.scaled_jacobian.min, 0.0);
  // The optimisation never lowers the minimum.
  EXPECT_GE(r.stats.min_sj, r.stats.min_sj_before_optimisation);
}

// The grid mesh of s at its size, with no error and valid (expect_valid).
grid::GridResult mesh_valid(const Named& s) {
  grid::GridOptions o;
  o.size = s.size;
  grid::GridResult r = grid::grid_mesh(s.solid, o);
  for (const core::Diagnostic& d : r.diagnostics)
    if (d.severity == core::Severity::error) ADD_FAILURE() << core::format(d);
  expect_valid(s.solid, r);
  return r;
}

TEST(GridFrame, AxesFollowTheLargestPlanarFaces) {
  // A box turned by 30 degrees about z: the grid's axes are its face normals, and its faces
  // are grid planes (so the box is a tensor grid of exact cells).
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  const Vec3 x(c, s, 0), y(-s, c, 0), z(0, 0, 1);
  std::vector<Vec3> p;
  for (int k = 0; k < 8; ++k)
    p.push_back(x * (k & 1 ? 4 : 0) + y * (k & 2 ? 3 : 0) + z * (k & 4 ? 2 : 0));
  const occ::Solid box = occ::make_polyhedron(
      {p[0], p[1], p[3], p[2], p[4], p[5], p[7], p[6]},
      {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}});
  const grid::detail::GridFrame f = grid::detail::grid_frame(box, boundary_points(box), 0.5);
  std::set<int> matched;
  for (const Vec3& a : f.axes)
    for (int i = 0; i < 3; ++i)
      if (std::abs(a.dot(std::array<Vec3, 3>{x, y, z}[i])) > 1 - 1e-9) matched.insert(i);
  EXPECT_EQ(matched.size(), 3u);
  EXPECT_NEAR(f.axes[0].cross(f.axes[1]).dot(f.axes[2]), 1.0, 1e-12);
  EXPECT_EQ(f.cells(0) * f.cells(1) * f.cells(2), 8 * 6 * 4);
}

TEST(CoreCells, CoreIsInsideAndManifold) {
  const occ::Solid cut_cube = testing::make_cut_cube();
  const double size = 0.25;
  const grid::detail::GridFrame f =
      grid::detail::grid_frame(cut_cube, boundary_points(cut_cube), size);
  occ::TessellationOptions o;
  o.linear_deflection = 0.01;
  const occ::Tessellation t = occ::tessellate(cut_cube, o);
  const grid::detail::CoreCells core = grid::detail::core_cells(f, cut_cube, t, size, 0.5, 0.01);
  // 8 x 8 x 8 cells of 0.25; the core is 6 x 6 x 6 one layer off the outer faces, less the
  // 4 x 4 x 4 cells that reach into the cut corner or its layer.
  EXPECT_EQ(core.cells, (std::array<int, 3>{8, 8, 8}));
  EXPECT_EQ(core.core, std::size_t(6 * 6 * 6 - 4 * 4 * 4));
  EXPECT_EQ(core.removed_components, 0u);
}

TEST(Pillow, OneLayerClosesTheCore) {
  const occ::Solid box = occ::make_box(2, 1, 1);
  const double size = 0.25;
  const grid::detail::GridFrame f = grid::detail::grid_frame(box, boundary_points(box), size);
  occ::TessellationOptions o;
  o.linear_deflection = 0.01;
  const occ::Tessellation t = occ::tessellate(box, o);
  const grid::detail::CoreCells core = grid::detail::core_cells(f, box, t, size, 0.5, 0.01);
  const grid::detail::PillowMesh p = grid::detail::pillow_mesh(f, core, box);
  EXPECT_EQ(p.core_hexes, std::size_t(6 * 2 * 2));
  // One pillow hex per core boundary quad: 2 (6x2 + 6x2 + 2x2).
  EXPECT_EQ(p.pillow_hexes, std::size_t(2 * (12 + 12 + 4)));
  const quality::CheckReport c = quality::check_mesh(p.mesh, nullptr);
  EXPECT_EQ(c.non_manifold_quads, 0u);
  EXPECT_EQ(c.open_boundary_edges, 0u);
  // A box aligned with the grid: core corners go to the model vertices, core edges to the
  // model edges, so the layer is valid before any feature capture.
  EXPECT_EQ(c.non_positive, 0u);
}

TEST(GridMesh, ValidOnMachinedAndCurvedSolids) {
  std::vector<Named> solids;
  solids.push_back({"box", occ::make_box(3, 2, 1), 0.25});
  solids.push_back({"thick L", testing::make_l(3), 0.25});
  solids.push_back({"cut cube", testing::make_cut_cube(), 0.25});
  solids.push_back({"cylinder", occ::make_cylinder(1, 2), 0.2});
  // Walls thinner than about three cells: the grid is refined once (size 3 -> 1.5).
  solids.push_back({"stepped plate with holes", testing::make_stepped_plate_with_holes(), 3});
  for (const char* name : {"s17o_sphere.step", "s07o_notch.step"}) {
    occ::ReadResult read = occ::read_solid(std::string(VOROHEX_HEXME_DIR) + "/" + name);
    ASSERT_TRUE(read.ok()) << name;
    solids.push_back({name, read.solid->clone(), read.solid->diagonal() / 20});
  }
  for (const Named& s : solids) {
    SCOPED_TRACE(s.name);
    const grid::GridResult r = mesh_valid(s);
    EXPECT_EQ(r.stats.vertices_captured, r.stats.vertices);
    EXPECT_EQ(r.stats.edges_captured, r.stats.edges);
    EXPECT_EQ(r.stats.faces_captured, r.stats.faces);
    // Every boundary node on its CAD entity (the check measures it against that entity).
    const quality::CheckReport c = quality::check_mesh(r.mesh, &s.solid);
    EXPECT_LT(c.max_boundary_distance_rel, 1e-7);
    EXPECT_GE(c.scaled_jacobian.min, 0.2);
  }
}

TEST(GridMesh, AlignedBoxIsOneCorePillowed) {
  const occ::Solid box = occ::make_box(3, 2, 1);
  grid::GridOptions o;
  o.size = 0.25;
  const grid::GridResult r = grid::grid_mesh(box, o);
  expect_valid(box, r);
  // A core of 10 x 6 x 2 cells and one pillow hex per core boundary quad.
  EXPECT_EQ(r.mesh.num_hexes(), std::size_t(10 * 6 * 2 + 2 * (60 + 20 + 12)));
  EXPECT_GT(r.stats.min_sj, 0.5);
}

// What the grid mesher cannot mesh validly yet (turned parts whose end faces it does not
// capture at this size) is never reported as a success: an inverted element left after
// the optimisation is the error grid_inverted, and through the pipeline the result is
// never ok unless the validity check passed.
TEST(GridMesh, AnInvalidResultIsNeverASuccess) {
  std::vector<Named> solids;
  solids.push_back({"stepped shaft", testing::make_stepped_shaft(), 0});
  solids.push_back({"chamfered shaft", testing::make_chamfered_shaft(), 0});
  for (const Named& s : solids) {
    SCOPED_TRACE(s.name);
    grid::GridOptions o;
    o.size = s.solid.diagonal() / 20;
    const grid::GridResult r = grid::grid_mesh(s.solid, o);
    const quality::CheckReport c = quality::check_mesh(r.mesh, &s.solid);
    if (c.non_positive > 0) {
      EXPECT_FALSE(r.ok);
      bool said = false;
      for (const core::Diagnostic& d : r.diagnostics)
        said = said || (d.code == "grid_inverted" && d.severity == core::Severity::error);
      EXPECT_TRUE(said);
    }
    pipeline::MeshOptions po;
    po.schemes = {"grid"};
    po.decompose = false;
    const pipeline::MeshResult p = pipeline::generate_mesh(s.solid, po);
    EXPECT_EQ(p.stats.scheme, "grid");
    if (p.ok) {
      EXPECT_TRUE(p.check.valid);
    }
    if (!p.check.valid) {
      EXPECT_FALSE(p.ok);
    }
  }
}

// A pit cut into a block (HexMe n06, a pentagonal pyramid; a square pyramid built here):
// near the pit's concave edges the pillow layer's outer nodes of two faces end pressed
// against the faces' common edge, each held at its own face's boundary, so the quads
// between them are flat and their hexes inverted. Untangling lets such a node cross onto
// the neighbouring face; the mesh is then valid: every scaled Jacobian positive, the
// layer conforming and closed, every boundary node on its CAD entity.
TEST(GridMesh, NodesHeldAtAFaceBoundaryCrossItWhileUntangling) {
  std::vector<Named> solids;
  const occ::ReadResult n06 =
      occ::read_solid(std::string(VOROHEX_HEXME_DIR) + "/n06o_anti_pentapyr.step");
  ASSERT_TRUE(n06.ok()) << "HexMe model n06 not found in " << VOROHEX_HEXME_DIR;
  solids.push_back({"n06", n06.solid->clone(), n06.solid->diagonal() / 20});
  const occ::Solid pit = testing::make_pyramid_pit();
  solids.push_back({"pyramid pit", pit.clone(), pit.diagonal() / 15});
  for (const Named& s : solids) {
    SCOPED_TRACE(s.name);
    const grid::GridResult r = mesh_valid(s);
    for (double sj : quality::scaled_jacobians(r.mesh)) ASSERT_GT(sj, 0.0);
    const quality::CheckReport c = quality::check_mesh(r.mesh, &s.solid);
    EXPECT_LT(c.max_boundary_distance_rel, 1e-7);
    // Before the optimisation the layer had inverted hexes: the crossing made the change.
    EXPECT_GT(r.stats.inverted_before_optimisation, 0u);
    EXPECT_GT(r.stats.min_sj, 0.1);
  }
}

// HexMe industrial parts the grid mesher left with inverted or flat hexes: i10 (outer quads
// cut along their diagonal by a curved edge, folded flat onto a plane: scaled Jacobian
// 1e-15) and i15 (pillow nodes pressed together at the boundary of a cylinder). The
// untangling takes on flat hexes, lets boundary nodes cross onto the neighbouring face and
// runs again after the optimisation: both are valid, every boundary node on its entity.
TEST(GridMesh, IndustrialPartsWithFoldedBoundaryQuadsEndValid) {
  for (const char* name : {"i10o_simp.step", "i15o_s8.step"}) {
    SCOPED_TRACE(name);
    const occ::ReadResult in = occ::read_solid(std::string(VOROHEX_HEXME_DIR) + "/" + name);
    ASSERT_TRUE(in.ok()) << name << " not found in " << VOROHEX_HEXME_DIR;
    grid::GridOptions o;
    o.size = in.solid->diagonal() / 20;
    const grid::GridResult r = grid::grid_mesh(*in.solid, o);
    expect_valid(*in.solid, r);
    const std::vector<double> sj = quality::scaled_jacobians(r.mesh);
    EXPECT_GT(*std::min_element(sj.begin(), sj.end()), 1e-6);  // none flat either
    EXPECT_GT(r.stats.inverted_before_optimisation, 0u);
    const quality::CheckReport c = quality::check_mesh(r.mesh, in.solid.get());
    EXPECT_LT(c.max_boundary_distance_rel, 1e-7);
  }
}

// A tube (radius 10 and 7, 50 long) with a cross hole of radius 3, as built in FreeCAD's
// Part workbench: its walls are 3 thick, so the grid refines to a quarter of the size, and
// the core's staircase keeps the outer nodes up to about two cells from the end circles and
// the hole's rims where it turns at 45 degrees to them. With chains allowed within 1.5 cells
// of their curve, those five edges had none: 331 quads cut across them, 1.1 % of the
// volume missing. Within 2.5 cells every edge has its chain and the mesh is valid.
TEST(GridMesh, ATubesCircularEdgesGetChainsAcrossTheStaircase) {
  const std::unique_ptr<occ::Solid> bore =
      occ::cut_solids(occ::make_cylinder(10, 50), occ::make_cylinder(7, 50));
  ASSERT_TRUE(bore);
  const std::unique_ptr<occ::Solid> tube =
      occ::cut_solids(*bore, occ::make_cylinder(3, 30, Vec3(-15, 0, 25), Vec3(1, 0, 0)));
  ASSERT_TRUE(tube);
  grid::GridOptions o;
  o.size = tube->diagonal() / 20;
  const grid::GridResult r = grid::grid_mesh(*tube, o);
  expect_valid(*tube, r);
  for (const core::Diagnostic& d : r.diagnostics)
    EXPECT_NE(d.code, "features_not_captured") << core::format(d);
  EXPECT_EQ(r.stats.edges_captured, r.stats.edges);
  const quality::CheckReport c = quality::check_mesh(r.mesh, tube.get());
  for (const core::Diagnostic& d : c.diagnostics)
    EXPECT_NE(d.code, "boundary_across_edges") << core::format(d);
  EXPECT_LT(c.volume_rel_error, 0.005);
}

// HexMe i14: at the first refinement the core fell apart and 150 cells (2.5% of the
// volume) away from the largest piece were left out, too few to count as a split (a quarter
// of the core): the mesh missed 12% of the volume. Pieces left out holding more than 1% of
// the volume refine the grid again: the mesh fills the solid and is valid.
TEST(GridMesh, CorePiecesLeftOutWithMuchVolumeRefineTheGrid) {
  const occ::ReadResult in = occ::read_solid(std::string(VOROHEX_HEXME_DIR) + "/i14o_s7.step");
  ASSERT_TRUE(in.ok()) << "HexMe model i14 not found in " << VOROHEX_HEXME_DIR;
  grid::GridOptions o;
  o.size = in.solid->diagonal() / 20;
  const grid::GridResult r = grid::grid_mesh(*in.solid, o);
  expect_valid(*in.solid, r);
  EXPECT_NEAR(r.stats.size_used, o.size / 4, 1e-9 * o.size);  // refined twice
  const quality::CheckReport c = quality::check_mesh(r.mesh, in.solid.get());
  EXPECT_TRUE(c.valid);
  EXPECT_LT(c.volume_rel_error, 0.01);
}

// A 10 x 5 x 2 box with the letters VHX engraved 0.05 deep (into its bottom face), at
// size 0.5: the engraving's walls and short edges are absorbed, not resolved, and said so;
// the mesh is valid (nodes on the real faces, volume within the chord allowance).
TEST(GridMesh, EngravingIsAbsorbedAndTheMeshValid) {
  using Outline = std::vector<std::array<double, 2>>;
  const std::vector<Outline> letters = {
      {{1, 3.8}, {1.3, 3.8}, {2, 1.6}, {2.7, 3.8}, {3, 3.8}, {2.15, 1.2}, {1.85, 1.2}},
      {{4, 1.2},
       {4.3, 1.2},
       {4.3, 2.35},
       {5.2, 2.35},
       {5.2, 1.2},
       {5.5, 1.2},
       {5.5, 3.8},
       {5.2, 3.8},
       {5.2, 2.65},
       {4.3, 2.65},
       {4.3, 3.8},
       {4, 3.8}},
      {{6.5, 1.2},
       {6.85, 1.2},
       {7.35, 2.2},
       {7.85, 1.2},
       {8.2, 1.2},
       {7.55, 2.5},
       {8.2, 3.8},
       {7.85, 3.8},
       {7.35, 2.8},
       {6.85, 3.8},
       {6.5, 3.8},
       {7.15, 2.5}}};
  occ::Solid part = occ::make_box(10, 5, 2);
  for (Outline o : letters) {
    double area2 = 0;  // counter-clockwise for make_prism
    for (std::size_t i = 0; i < o.size(); ++i)
      area2 += o[i][0] * o[(i + 1) % o.size()][1] - o[(i + 1) % o.size()][0] * o[i][1];
    if (area2 < 0) std::reverse(o.begin(), o.end());
    part = testing::cut(part, occ::make_prism(o, 0.05));
  }
  ASSERT_GT(part.num_faces(), 30);
  // (Its time is measured in bench/results/parts.md, not asserted here.)
  pipeline::MeshOptions po;
  po.size = 0.5;
  po.schemes = {"grid"};
  po.decompose = false;
  const pipeline::MeshResult r = pipeline::generate_mesh(part, po);
  for (const core::Diagnostic& d : r.diagnostics)
    if (d.severity == core::Severity::error) ADD_FAILURE() << core::format(d);
  EXPECT_TRUE(r.ok);
  EXPECT_TRUE(r.check.valid);
  EXPECT_GT(r.check.scaled_jacobian.min, 0.2);
  const core::Diagnostic* absorbed = nullptr;
  for (const core::Diagnostic& d : r.diagnostics)
    if (d.code == "features_absorbed") absorbed = &d;
  ASSERT_NE(absorbed, nullptr);
  EXPECT_EQ(absorbed->severity, core::Severity::warning);
  EXPECT_GT(absorbed->entities.size(), 20u);
}

TEST(GridMesh, FallbackSchemeIsAnOption) {
  pipeline::MeshOptions o;
  EXPECT_EQ(o.fallback_scheme, "grid");
  o.fallback_scheme = "tet-split";
  EXPECT_NO_THROW(o.validate());
  o.fallback_scheme = "octree";
  EXPECT_THROW(o.validate(), std::invalid_argument);
}

TEST(GridMesh, OptionsAreValidated) {
  grid::GridOptions o;
  o.size = 0;
  EXPECT_THROW(o.validate(), std::invalid_argument);
  o.size = 1;
  o.core_margin = -1;
  EXPECT_THROW(o.validate(), std::invalid_argument);
  o.core_margin = 0.5;
  o.quality_target = 2;
  EXPECT_THROW(o.validate(), std::invalid_argument);
  o.quality_target = 0.5;
  o.max_levels = 5;
  EXPECT_THROW(o.validate(), std::invalid_argument);
  o.max_levels = 2;
  o.max_local_cells = 0;
  EXPECT_THROW(o.validate(), std::invalid_argument);
  o.max_local_cells = 1000;
  EXPECT_NO_THROW(o.validate());
}

TEST(GridMesh, TooManyHexesIsRefusedBeforeMeshing) {
  const occ::Solid box = occ::make_box(3, 2, 1);
  grid::GridOptions o;
  o.size = 0.01;
  o.max_hexes = 1000;
  const grid::GridResult r = grid::grid_mesh(box, o);
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_EQ(r.diagnostics.back().code, "too_many_hexes");
}

// A model of tests/data/hexme and its grid mesh at the default size (diagonal / 20), with
// the grid's info message; `in` is not ok when the file is missing.
struct HexMeGrid {
  occ::ReadResult in;
  grid::GridResult mesh;
  std::string info;
};

HexMeGrid hexme_grid(const std::string& file) {
  HexMeGrid h;
  h.in = occ::read_solid(std::string(VOROHEX_HEXME_DIR) + "/" + file);
  if (!h.in.ok()) return h;
  grid::GridOptions o;
  o.size = h.in.solid->diagonal() / 20;
  h.mesh = grid::grid_mesh(*h.in.solid, o);
  for (const core::Diagnostic& d : h.mesh.diagnostics)
    if (d.code == "grid") h.info = d.message;
  return h;
}

TEST(GridMesh, EdgesLeavingAVertexTangentToAnotherShareItsChainOnHexMeI20) {
  // HexMe i20: four quarter circles (radius 40) leave their vertices tangent to straight
  // edges. For the first cells both chains need the nodes along the line; the arcs were not
  // captured, a pillow hexahedron straddled one of them and stayed inverted. Now an arc's
  // chain shares the line's nodes there (they stay on the line) and the mesh is valid.
  const HexMeGrid h = hexme_grid("i20o_s25.step");
  ASSERT_TRUE(h.in.ok()) << "HexMe model i20 not found in " << VOROHEX_HEXME_DIR;
  expect_valid(*h.in.solid, h.mesh);
  EXPECT_NE(h.info.find("sharing nodes of another edge's chain"), std::string::npos) << h.info;
  EXPECT_GE(h.mesh.stats.edges_captured, h.mesh.stats.edges - 6) << h.info;
  EXPECT_GT(h.mesh.stats.min_sj, 0.2);
}

TEST(GridMesh, TangentEdgesTakeTheirChainsLastWhereTheyBlockASharpEdgeOnHexMeS10) {
  // HexMe s10: a dome on a cylinder of its radius (the equator a tangent edge), a quarter of
  // it cut away by two planes. In the model's order the equator's chain took the nodes the
  // arcs where the planes meet the dome needed at its vertices; the arcs were not captured
  // and the mesh cut 2.5 % of the volume off. With the tangent edges' chains made after the
  // others every feature is captured, and the mesh is valid.
  const HexMeGrid h = hexme_grid("s10o_cyl_cutsphere.step");
  ASSERT_TRUE(h.in.ok()) << "HexMe model s10 not found in " << VOROHEX_HEXME_DIR;
  expect_valid(*h.in.solid, h.mesh);
  EXPECT_EQ(h.mesh.stats.features_missed, 0u) << h.info;
  EXPECT_NE(h.info.find("tangent edges' chains made after the others"), std::string::npos)
      << h.info;
  EXPECT_GT(h.mesh.stats.min_sj, 0.2);
}

TEST(GridMesh, AVertexAnEdgeRunsStraightThroughTakesTwoQuadsOnTheFlatSideOnHexMeS10) {
  // HexMe s10: the circle where the cylinder meets the dome runs on straight through
  // Vertex2, where the plane cutting the quarter away meets it; the cylinder's angle there
  // is 180 degrees. On a core corner's node (three quads, one per face) the cylinder's quad
  // at the vertex had both chains along two of its sides, flat (min 0.24). Such an angle now
  // asks for two quads, as a reflex one does: the vertex takes a node with four.
  const HexMeGrid h = hexme_grid("s10o_cyl_cutsphere.step");
  ASSERT_TRUE(h.in.ok()) << "HexMe model s10 not found in " << VOROHEX_HEXME_DIR;
  expect_valid(*h.in.solid, h.mesh);
  EXPECT_EQ(h.mesh.stats.features_missed, 0u) << h.info;
  EXPECT_GT(h.mesh.stats.min_sj, 0.4) << h.info;
}

TEST(GridMesh, VerticesTakeNodesWithAnOuterEdgeForEachOfTheirEdgesOnHexMeN15) {
  // HexMe n15, an icosahedron: five edges at every vertex. A vertex on a core corner's
  // outer node (three outer edges) left chains no way out: 24 of 30 edges captured, min
  // 0.19. Nodes with as many outer edges as the vertex has edges are preferred: 26, 0.41.
  const HexMeGrid h = hexme_grid("n15o_icosahedron.step");
  ASSERT_TRUE(h.in.ok()) << "HexMe model n15 not found in " << VOROHEX_HEXME_DIR;
  expect_valid(*h.in.solid, h.mesh);
  EXPECT_EQ(h.mesh.stats.vertices_captured, 12) << h.info;
  EXPECT_GE(h.mesh.stats.edges_captured, 26) << h.info;
  EXPECT_GT(h.mesh.stats.min_sj, 0.3);
}

TEST(GridMesh, AVertexWhereAFloorsAngleIsReflexTakesANodeWithAQuadMoreOnHexMeI17) {
  // HexMe i17 at a third of its grid's size (the pipeline's finer grid): walls meet a floor
  // at vertices where the floor's interior angle is 191 degrees. Such a vertex on a core
  // corner's node (three quads: one per wall, one for the floor) left the floor's quad bent
  // inside out there, and two hexahedra stayed inverted. A node with a quad more for the
  // reflex angle is preferred: the mesh is valid.
  const auto in = occ::read_solid(std::string(VOROHEX_HEXME_DIR) + "/i17o_s20.step");
  ASSERT_TRUE(in.ok()) << "HexMe model i17 not found in " << VOROHEX_HEXME_DIR;
  grid::GridOptions o;
  o.size = in.solid->diagonal() / 120;  // the default size / 2 (the grid halves it) / 3
  const grid::GridResult r = grid::grid_mesh(*in.solid, o);
  expect_valid(*in.solid, r);
  EXPECT_EQ(r.stats.features_missed, 0u);
  EXPECT_GT(r.stats.min_sj, 0.3);
}

TEST(GridMesh, ChainsAtACuspShareNodesOnHexMeI03) {
  // HexMe i03 at a third of its grid's size (the pipeline's finer grid): its planar Face10
  // comes to a point at Vertex71, where the circle Edge80 leaves the line Edge87 tangentially,
  // and the two run within a cell of each other for several cells. With a chain along each,
  // the quads between them were flat (min 0.001). Sharing nodes while the chains lie within
  // 0.3 cells of each other leaves that tip of the face without quads: min 0.26.
  const auto in = occ::read_solid(std::string(VOROHEX_HEXME_DIR) + "/i03o_m3.step");
  ASSERT_TRUE(in.ok()) << "HexMe model i03 not found in " << VOROHEX_HEXME_DIR;
  grid::GridOptions o;
  o.size = in.solid->diagonal() / 240;  // the default size / 4 (the grid halves it twice) / 3
  o.share_cusps = true;
  const grid::GridResult r = grid::grid_mesh(*in.solid, o);
  expect_valid(*in.solid, r);
  const core::Vec3 vertex71(35.0, 17.613959659231, -73.12379288883);
  EXPECT_TRUE(std::any_of(r.stats.cusp_points.begin(), r.stats.cusp_points.end(),
                          [&](const core::Vec3& p) { return (p - vertex71).norm() < 1e-6; }));
  std::string info;
  for (const core::Diagnostic& d : r.diagnostics)
    if (d.code == "grid") info = d.message;
  EXPECT_NE(info.find("sharing nodes of another edge's chain"), std::string::npos) << info;
  EXPECT_GT(r.stats.min_sj, 0.2);
}

TEST(GridMesh, AGridALittleFinerCapturesWhatHexMeI25sMissed) {
  // HexMe i25 at its finer grid's size (the default / 3) leaves three edges uncaptured and
  // its worst hexahedron at 0.007; the pipeline makes such a mesh again on a grid 0.93 times
  // its size (pipeline/detail/fallback.cpp, jittered_grid), where the cells fall differently
  // at the model's vertices and edges: every feature captured, min 0.3.
  const auto in = occ::read_solid(std::string(VOROHEX_HEXME_DIR) + "/i25o_s40.step");
  ASSERT_TRUE(in.ok()) << "HexMe model i25 not found in " << VOROHEX_HEXME_DIR;
  grid::GridOptions o;
  o.size = in.solid->diagonal() / 60;
  const grid::GridResult finer = grid::grid_mesh(*in.solid, o);
  ASSERT_TRUE(finer.ok);
  EXPECT_GT(finer.stats.features_missed, 0u);
  EXPECT_LT(finer.stats.min_sj, 0.2);
  o.size *= 0.93;
  const grid::GridResult jittered = grid::grid_mesh(*in.solid, o);
  expect_valid(*in.solid, jittered);
  EXPECT_EQ(jittered.stats.features_missed, 0u);
  EXPECT_GT(jittered.stats.min_sj, 0.2);
}

TEST(GridMesh, AFinerGridCapturesTheThinCrossCylinderOfHexMeS08) {
  // HexMe s08: a cylinder crossed by one of half its radius, 2.7 cells across at the
  // default size: no core of its own, its end circles 4.5 cells from any outer node, not
  // captured, and the mesh cuts 13 % of the volume off. At a third of the size (the
  // pipeline's finer grid, GenerateMesh.AnInvalidGridMeshIsMadeAgainOnAFinerGrid) the grid
  // captures them.
  const HexMeGrid h = hexme_grid("s08o_cross_cyls_dr.step");
  ASSERT_TRUE(h.in.ok()) << "HexMe model s08 not found in " << VOROHEX_HEXME_DIR;
  const grid::GridResult& first = h.mesh;
  ASSERT_TRUE(first.ok);
  EXPECT_GT(first.stats.features_missed, 2u);
  EXPECT_GT(quality::check_mesh(first.mesh, h.in.solid.get()).volume_rel_error, 0.05);
  grid::GridOptions o;
  o.size = first.stats.size_used / 3;
  const grid::GridResult finer = grid::grid_mesh(*h.in.solid, o);
  EXPECT_LT(finer.stats.features_missed, first.stats.features_missed);
  expect_valid(*h.in.solid, finer);
}

}  // namespace
}  // namespace vorohex
