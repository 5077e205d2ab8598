// The "Must show" list of issue 4 on solids built with OCCT.
#include "voronoi/voronoi_graph.h"

#include <gtest/gtest.h>

#include "fixtures/solids.h"

#include <functional>
#include <random>
#include <set>

#include "occ/primitives.h"
#include "voronoi/detail/distance_field.h"

namespace vorohex::voronoi {
namespace {

using model::EntityKind;

VoronoiResult run(const occ::Solid& solid, VoronoiOptions opt = {}) {
  VoronoiResult r = compute_voronoi_graph(solid, opt);
  EXPECT_TRUE(r.ok());
  for (const auto& d : r.diagnostics) ADD_FAILURE() << core::format(d);
  return r;
}

std::string describe(const VoronoiGraph& g) {
  std::string s;
  for (const auto& e : g.elements) {
    s += element_kind_name(e.kind);
    s += ":";
    for (const auto& gv : e.governors) s += " " + gv.name();
    s += "\n";
  }
  return s;
}

int count_faces(const std::vector<EntityRef>& govs) {
  int n = 0;
  for (const auto& g : govs) n += g.kind == EntityKind::face;
  return n;
}

// Every placed vertex is equidistant from its governors within delta and no entity of the
// solid (checked with OCCT's exact distances) is nearer by more than delta.
void expect_vertices_exact(const occ::Solid& solid, const VoronoiResult& r, double delta_rel) {
  const double delta = delta_rel * solid.diagonal();
  for (int v : r.graph.of_kind(ElementKind::vertex)) {
    const VoronoiElement& el = r.graph.elements[v];
    EXPECT_TRUE(el.verified);
    std::vector<double> d;
    for (const EntityRef& g : el.governors) {
      if (g.kind == EntityKind::face)
        d.push_back(solid.distance_to_face(core::FaceId(g.id), el.point));
      if (g.kind == EntityKind::edge)
        d.push_back(solid.distance_to_edge(core::EdgeId(g.id), el.point));
      if (g.kind == EntityKind::vertex)
        d.push_back(solid.distance_to_vertex(core::VertexId(g.id), el.point));
    }
    const double lo = *std::min_element(d.begin(), d.end());
    const double hi = *std::max_element(d.begin(), d.end());
    EXPECT_LE(hi - lo, delta);
    EXPECT_GE(solid.distance_to_boundary(el.point), lo - delta);
  }
}

TEST(VoronoiGraph, Box321HasOneFsFaceBetweenTheLargestFaces) {
  const occ::Solid box = occ::make_box(3, 2, 1);
  const VoronoiResult r = run(box);
  const auto fs = r.graph.fs_faces();
  ASSERT_EQ(fs.size(), 1u) << describe(r.graph);
  const VoronoiElement& f = r.graph.elements[fs[0]];
  ASSERT_EQ(f.governors.size(), 2u);
  for (const EntityRef& g : f.governors) {
    ASSERT_EQ(g.kind, EntityKind::face);
    EXPECT_NEAR(box.area(core::FaceId(g.id)), 6.0, 1e-9);  // the 3 x 2 faces
  }
  // Its boundary: four edges, each governed by the two large faces and one side face,
  // meeting at four vertices.
  EXPECT_EQ(r.graph.bounding_edges(fs[0]).size(), 4u) << describe(r.graph);
  EXPECT_EQ(r.graph.of_kind(ElementKind::vertex).size(), 4u) << describe(r.graph);
  expect_vertices_exact(box, r, VoronoiOptions{}.delta);
}

TEST(VoronoiGraph, CubeHasOneDegenerateVertexAndNoFsFace) {
  const occ::Solid cube = occ::make_box(1, 1, 1);
  const VoronoiResult r = run(cube);
  EXPECT_TRUE(r.graph.fs_faces().empty()) << describe(r.graph);
  const auto vertices = r.graph.of_kind(ElementKind::vertex);
  ASSERT_EQ(vertices.size(), 1u) << describe(r.graph);
  const VoronoiElement& v = r.graph.elements[vertices[0]];
  EXPECT_EQ(v.governors.size(), 6u);
  EXPECT_EQ(count_faces(v.governors), 6);
  EXPECT_LT((v.point - Vec3(0.5, 0.5, 0.5)).norm(), 1e-6);
  // Eight [C] edges run from the centre to the corners.
  EXPECT_EQ(r.graph.of_kind(ElementKind::edge).size(), 8u) << describe(r.graph);
  expect_vertices_exact(cube, r, VoronoiOptions{}.delta);
}

TEST(VoronoiGraph, LongTriangularPrismHasAnEdgeOfTheThreeSideFaces) {
  const occ::Solid prism = occ::make_prism({{0, 0}, {1, 0}, {0.5, 0.8}}, 10);
  const VoronoiResult r = run(prism);
  std::vector<EntityRef> sides;
  for (const core::FaceId f : prism.faces())
    if (prism.area(f) > 5) sides.push_back(model::ref(f));
  ASSERT_EQ(sides.size(), 3u);
  const auto found = r.graph.find(sides);
  ASSERT_EQ(found.size(), 1u) << describe(r.graph);
  const VoronoiElement& e = r.graph.elements[found[0]];
  EXPECT_EQ(e.kind, ElementKind::edge);
  EXPECT_TRUE(e.verified);
  // It runs along the prism, through the incentre of the triangle.
  ASSERT_GE(e.polyline.size(), 2u);
  double zmin = 1e9, zmax = -1e9;
  for (const Vec3& p : e.polyline) {
    zmin = std::min(zmin, p.z());
    zmax = std::max(zmax, p.z());
  }
  EXPECT_GT(zmax - zmin, 8.0);
}

occ::Solid make_l_shape() {
  // Legs 1 thick, 4 and 3 long, depth 3.
  return occ::make_prism({{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 3}, {0, 3}}, 3);
}

TEST(VoronoiGraph, LShapeHasElementsGovernedByTheConcaveEdge) {
  const occ::Solid l = make_l_shape();
  const VoronoiResult r = run(l);
  // The concave edge is the vertical edge at (1, 1).
  const auto& m = *r.model;
  int concave = 0;
  EntityRef edge;
  for (const auto& e : m.edges())
    if (e.convexity == model::Convexity::concave) {
      ++concave;
      edge = model::ref(e.id);
      EXPECT_NEAR(e.dihedral, 1.5 * M_PI, 1e-6);
    }
  ASSERT_EQ(concave, 1);
  int edges_2f1e = 0, vertices_3f1e = 0;
  for (const VoronoiElement& el : r.graph.elements) {
    const bool has_edge =
        std::find(el.governors.begin(), el.governors.end(), edge) != el.governors.end();
    if (!has_edge) continue;
    if (el.kind == ElementKind::edge && el.governors.size() == 3 && count_faces(el.governors) == 2)
      ++edges_2f1e;
    if (el.kind == ElementKind::vertex && el.governors.size() == 4 &&
        count_faces(el.governors) == 3)
      ++vertices_3f1e;
  }
  EXPECT_GE(edges_2f1e, 4) << describe(r.graph);
  EXPECT_EQ(vertices_3f1e, 6) << describe(r.graph);
  EXPECT_EQ(r.graph.of_kind(ElementKind::vertex).size(), 10u) << describe(r.graph);
  expect_vertices_exact(l, r, VoronoiOptions{}.delta);
}

TEST(VoronoiGraph, CylinderLateralFaceIsOneGovernor) {
  const occ::Solid cyl = occ::make_cylinder(1, 1);  // short: top|bottom face exists
  const VoronoiResult r = run(cyl);
  core::FaceId lateral;
  for (const core::FaceId f : cyl.faces())
    if (!cyl.face_is_planar(f)) lateral = f;
  ASSERT_TRUE(lateral.value() > 0);
  ASSERT_GT(r.model->linear().polygons.size(), 10u);  // it was linearised
  int with_lateral = 0;
  for (const VoronoiElement& el : r.graph.elements) {
    std::set<EntityRef> distinct(el.governors.begin(), el.governors.end());
    EXPECT_EQ(distinct.size(), el.governors.size());
    EXPECT_GE(el.governors.size(), 2u);
    for (const EntityRef& g : el.governors) {
      EXPECT_EQ(g.kind, EntityKind::face) << describe(r.graph);  // circles are convex
      with_lateral += g == model::ref(lateral);
    }
  }
  // Lateral|top, lateral|bottom and top|bottom faces, and the circle where they meet.
  EXPECT_EQ(r.graph.of_kind(ElementKind::face).size(), 3u) << describe(r.graph);
  EXPECT_EQ(r.graph.of_kind(ElementKind::edge).size(), 1u) << describe(r.graph);
  EXPECT_GE(with_lateral, 3);
}

// Brute-force owner with OCCT's exact distances: the lowest-dimensional entity among the
// nearest ones (its relative interior holds the nearest point).
EntityRef brute_owner(const occ::Solid& s, const Vec3& p, double* gap) {
  std::vector<std::pair<double, EntityRef>> d;
  for (auto f : s.faces()) d.push_back({s.distance_to_face(f, p), model::ref(f)});
  for (auto e : s.edges()) d.push_back({s.distance_to_edge(e, p), model::ref(e)});
  for (auto v : s.vertices()) d.push_back({s.distance_to_vertex(v, p), model::ref(v)});
  const double best = std::min_element(d.begin(), d.end())->first;
  const double tie = 1e-9 * s.diagonal();
  EntityRef owner{EntityKind::face, 0};
  for (const auto& [dist, e] : d)
    if (dist <= best + tie && (owner.id == 0 || e.kind > owner.kind)) owner = e;
  // Gap to the nearest entity not containing the nearest point is hard to get from OCCT;
  // the caller uses the subdivision's own margin instead.
  *gap = best;
  return owner;
}

// 10,000 random interior points at least delta from every Voronoi element (the gap to the
// second-nearest region is at least 2 delta and the gap is 2-Lipschitz): the region the
// subdivision assigns agrees with the brute-force nearest entity for >= 99.9%.
void expect_regions_agree(const occ::Solid& solid, const std::function<bool(const Vec3&)>& inside) {
  const VoronoiOptions opt;
  const VoronoiResult r = compute_voronoi_graph(solid, opt);
  ASSERT_TRUE(r.ok());
  detail::DistanceField field(*r.model);
  const double delta = opt.delta * solid.diagonal();
  const core::BoundingBox box = solid.bounding_box();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  int tested = 0, agree = 0;
  while (tested < 10000) {
    const Vec3 p = box.min + (box.max - box.min).cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
    if (!inside(p)) continue;
    double dist, margin;
    if (field.owner(p, &dist, &margin) < 0 || margin < 2 * delta) continue;
    double best;
    const EntityRef expected = brute_owner(solid, p, &best);
    ++tested;
    agree += r.locator->region(p) == expected;
  }
  EXPECT_GE(agree, 9990) << agree << " of " << tested;
}

TEST(VoronoiGraph, RegionsAgreeWithBruteForceNearestEntity) {
  expect_regions_agree(make_l_shape(), [](const Vec3& p) { return p.x() < 1 || p.y() < 1; });
}

TEST(VoronoiGraph, ConcaveVertexGovernsARegion) {
  const occ::Solid cut = vorohex::testing::make_cut_cube();
  // Several Voronoi vertices lie within a few eps of each other near (0.6, 0.6, 0.6) and
  // the extraction merges some of them into one degenerate element (a warning, known
  // limitation); the regions themselves must still be right.
  const VoronoiResult r = compute_voronoi_graph(cut);
  ASSERT_TRUE(r.ok());
  EntityRef corner;
  for (const auto& v : r.model->vertices())
    if (v.concave) corner = model::ref(v.id);
  ASSERT_GT(corner.id, 0);
  int with_corner = 0;
  for (const VoronoiElement& el : r.graph.elements)
    with_corner +=
        std::find(el.governors.begin(), el.governors.end(), corner) != el.governors.end();
  // Its region borders the three concave edges' regions at least.
  EXPECT_GE(with_corner, 3) << describe(r.graph);
  const Vec3 inside_corner(0.8, 0.8, 0.8);  // nearest boundary point is (1, 1, 1)
  EXPECT_EQ(r.locator->region(inside_corner), corner);
  expect_regions_agree(cut, [](const Vec3& p) { return !(p.x() > 1 && p.y() > 1 && p.z() > 1); });
}

// Subtrees are built by several threads and merged in a fixed order: the graph, the
// statistics and the regions do not depend on the thread count.
TEST(VoronoiGraph, ThreadCountDoesNotChangeTheResult) {
  const occ::Solid cut = vorohex::testing::make_cut_cube();
  VoronoiOptions one, three;
  one.threads = 1;
  three.threads = 3;
  const VoronoiResult a = compute_voronoi_graph(cut, one);
  const VoronoiResult b = compute_voronoi_graph(cut, three);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a.stats.cells, b.stats.cells);
  EXPECT_EQ(a.stats.finest_cells, b.stats.finest_cells);
  EXPECT_EQ(a.stats.distance_evaluations, b.stats.distance_evaluations);
  ASSERT_EQ(a.graph.elements.size(), b.graph.elements.size());
  for (size_t i = 0; i < a.graph.elements.size(); ++i) {
    const VoronoiElement &x = a.graph.elements[i], &y = b.graph.elements[i];
    EXPECT_EQ(x.kind, y.kind);
    EXPECT_EQ(x.governors, y.governors);
    EXPECT_EQ(x.point, y.point);
    EXPECT_EQ(x.polyline, y.polyline);
    EXPECT_EQ(x.verified, y.verified);
    EXPECT_EQ(x.incident, y.incident);
  }
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 2);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 p(u(rng), u(rng), u(rng));
    EXPECT_EQ(a.locator->region(p), b.locator->region(p));
  }
  VoronoiOptions bad;
  bad.threads = -1;
  EXPECT_FALSE(compute_voronoi_graph(cut, bad).ok());
}

TEST(VoronoiGraph, InvalidOptionsAreReported) {
  VoronoiOptions opt;
  opt.eps = -1;
  const VoronoiResult r = compute_voronoi_graph(occ::make_box(1, 1, 1), opt);
  EXPECT_FALSE(r.ok());
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_EQ(r.diagnostics[0].code, "invalid_options");
}

}  // namespace
}  // namespace vorohex::voronoi
