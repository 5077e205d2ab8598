#include "model/brep_model.h"

#include <gtest/gtest.h>

#include "fixtures/solids.h"

#include <cmath>

#include "occ/primitives.h"

namespace vorohex::model {
namespace {

TEST(BRepModel, BoxTopologyIncidenceAndAdjacency) {
  const ModelResult r = build_model(occ::make_box(3, 2, 1));
  ASSERT_TRUE(r.ok());
  const BRepModel& m = *r.model;
  EXPECT_EQ(m.faces().size(), 6u);
  EXPECT_EQ(m.edges().size(), 12u);
  EXPECT_EQ(m.vertices().size(), 8u);
  EXPECT_EQ(m.num_entities(), 26);
  for (int i = 0; i < m.num_entities(); ++i) EXPECT_EQ(m.index(m.entity(i)), i);
  for (const ModelEdge& e : m.edges()) {
    EXPECT_EQ(e.convexity, Convexity::convex);
    EXPECT_NEAR(e.dihedral, M_PI / 2, 1e-9);
    EXPECT_EQ(e.faces.size(), 2u);
    // An edge is incident on its faces and its vertices (both ways).
    for (FaceId f : e.faces) EXPECT_TRUE(m.incident(ref(e.id), ref(f)));
    EXPECT_TRUE(m.incident(ref(e.first), ref(e.id)));
  }
  for (const ModelVertex& v : m.vertices()) {
    EXPECT_FALSE(v.concave);
    EXPECT_EQ(v.edges.size(), 3u);
    EXPECT_EQ(v.faces.size(), 3u);
  }
  // Each face: 4 edge neighbours sharing an edge (adjacent), 1 opposite (unconnected).
  for (const ModelFace& f : m.faces()) {
    EXPECT_TRUE(f.planar);
    EXPECT_NEAR(f.normal.norm(), 1.0, 1e-12);
    EXPECT_EQ(f.edges.size(), 4u);
    EXPECT_EQ(f.vertices.size(), 4u);
    int adjacent = 0, unconnected = 0;
    for (const ModelFace& g : m.faces()) {
      if (g.id == f.id) continue;
      EXPECT_FALSE(m.incident(ref(f.id), ref(g.id)));
      adjacent += m.adjacent(ref(f.id), ref(g.id));
      unconnected += m.unconnected(ref(f.id), ref(g.id));
    }
    EXPECT_EQ(adjacent, 4);
    EXPECT_EQ(unconnected, 1);
    // Outward normal: the face centre plus the normal leaves the box.
    const Vec3 c = m.vertex(f.vertices[0]).point;
    const Vec3 out = c + 0.1 * f.normal;
    EXPECT_TRUE(out.x() < 0 || out.x() > 3 || out.y() < 0 || out.y() > 2 || out.z() < 0 ||
                out.z() > 1);
  }
  // A face and an edge of the opposite face share nothing; an edge of a side face does.
  const ModelEdge& e0 = m.edges()[0];
  for (const ModelFace& f : m.faces()) {
    const bool has_vertex =
        std::find(f.vertices.begin(), f.vertices.end(), e0.first) != f.vertices.end() ||
        std::find(f.vertices.begin(), f.vertices.end(), e0.last) != f.vertices.end();
    const bool bounds = std::find(f.edges.begin(), f.edges.end(), e0.id) != f.edges.end();
    EXPECT_EQ(m.adjacent(ref(e0.id), ref(f.id)), has_vertex && !bounds);
  }
  // Governing entities: faces only.
  for (int i = 0; i < m.num_entities(); ++i)
    EXPECT_EQ(m.governs_interior(m.entity(i)), m.entity(i).kind == EntityKind::face);
}

TEST(BRepModel, LShapeHasOneConcaveEdgeAndNoConcaveVertex) {
  const ModelResult r =
      build_model(occ::make_prism({{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 3}, {0, 3}}, 3));
  ASSERT_TRUE(r.ok());
  const BRepModel& m = *r.model;
  int concave = 0;
  for (const ModelEdge& e : m.edges())
    if (e.convexity == Convexity::concave) {
      ++concave;
      EXPECT_NEAR(e.dihedral, 1.5 * M_PI, 1e-6);
      EXPECT_NEAR(m.vertex(e.first).point.x(), 1.0, 1e-9);
      EXPECT_NEAR(m.vertex(e.first).point.y(), 1.0, 1e-9);
      EXPECT_TRUE(m.governs_interior(ref(e.id)));
    }
  EXPECT_EQ(concave, 1);
  // The concave edge's end vertices have a reflex face corner: no ball touches them alone.
  for (const ModelVertex& v : m.vertices()) EXPECT_FALSE(v.concave);
  // The top and bottom faces are single polygons with six corners.
  int hexagons = 0;
  for (const LinearPolygon& p : m.linear().polygons)
    hexagons += p.loops.size() == 1 && p.loops[0].size() == 6;
  EXPECT_EQ(hexagons, 2);
}

TEST(BRepModel, CornerCutFromACubeIsAConcaveVertex) {
  const ModelResult r = build_model(vorohex::testing::make_cut_cube());
  ASSERT_TRUE(r.ok());
  const BRepModel& m = *r.model;
  int concave_vertices = 0, concave_edges = 0;
  for (const ModelVertex& v : m.vertices())
    if (v.concave) {
      ++concave_vertices;
      EXPECT_LT((v.point - Vec3(1, 1, 1)).norm(), 1e-9);
      EXPECT_TRUE(m.governs_interior(ref(v.id)));
    }
  for (const ModelEdge& e : m.edges()) concave_edges += e.convexity == Convexity::concave;
  EXPECT_EQ(concave_vertices, 1);
  EXPECT_EQ(concave_edges, 3);
}

TEST(BRepModel, CylinderIsLinearisedWithOrigins) {
  const ModelResult r = build_model(occ::make_cylinder(1, 2));
  ASSERT_TRUE(r.ok());
  const BRepModel& m = *r.model;
  int lateral = 0;
  for (const ModelFace& f : m.faces())
    if (!f.planar) lateral = f.id.value();
  ASSERT_GT(lateral, 0);
  const double tol = m.options().linear_tolerance * m.diagonal();
  int facets = 0;
  for (const LinearPolygon& p : m.linear().polygons) {
    if (p.origin.id != lateral) continue;
    ++facets;
    // Facet corners lie on the cylinder, the facet is within the tolerance of it.
    Vec3 c(0, 0, 0);
    for (int i : p.loops[0]) {
      const Vec3& q = m.linear().points[i];
      EXPECT_NEAR(std::hypot(q.x(), q.y()), 1.0, 1e-6);
      c += q / 3.0;
    }
    EXPECT_GT(std::hypot(c.x(), c.y()), 1.0 - 1.5 * tol);
    EXPECT_GT(p.normal.dot(Vec3(c.x(), c.y(), 0).normalized()), 0.8);  // outward
  }
  EXPECT_GT(facets, 10);
  // Segments inside the lateral face are convex seen from inside; circle segments belong
  // to the circle edges, which are convex.
  for (const LinearSegment& s : m.linear().segments) EXPECT_FALSE(s.concave);
  for (const ModelEdge& e : m.edges())
    if (e.faces.size() == 2) EXPECT_EQ(e.convexity, Convexity::convex) << e.id.value();
}

TEST(BRepModel, PlateWithHoleKeepsTheHoleLoop) {
  const ModelResult r = build_model(
      occ::make_prism({{0, 0}, {4, 0}, {4, 3}, {0, 3}}, 1, {{{1, 1}, {2, 1}, {2, 2}, {1, 2}}}));
  ASSERT_TRUE(r.ok());
  const BRepModel& m = *r.model;
  int with_hole = 0, concave = 0;
  for (const LinearPolygon& p : m.linear().polygons) with_hole += p.loops.size() == 2;
  for (const ModelEdge& e : m.edges()) concave += e.convexity == Convexity::concave;
  EXPECT_EQ(with_hole, 2);
  EXPECT_EQ(concave, 4);  // the hole's vertical edges
}

TEST(BRepModel, InvalidOptions) {
  ModelOptions o;
  o.linear_tolerance = 0;
  EXPECT_FALSE(o.validate().empty());
  const ModelResult r = build_model(occ::make_box(1, 1, 1), o);
  EXPECT_FALSE(r.ok());
  ASSERT_EQ(r.diagnostics.size(), 1u);
  EXPECT_EQ(r.diagnostics[0].code, "invalid_options");
}

}  // namespace
}  // namespace vorohex::model
