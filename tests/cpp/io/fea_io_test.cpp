// Issue 21: element types, named groups per CAD entity and second-order hexahedra in the
// writers and readers.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <sstream>

#include "io/element_type.h"
#include "io/io_test_util.h"
#include "io/mesh_io.h"
#include "io/named_groups.h"
#include "io/second_order.h"
#include "occ/primitives.h"
#include "pipeline/generate_mesh.h"
#include "quality/check_mesh.h"
#include "quality/linear_gauss_jacobian.h"
#include "quality/quadratic_jacobian.h"
#include "quality/scaled_jacobian.h"

namespace vorohex::io {
namespace {

using testing::read_text;
using testing::temp_path;

// A box meshed by the pipeline (nodes classified on the box's faces, edges, vertices).
pipeline::MeshResult mesh_box(const occ::Solid& box, double size, int order = 1) {
  pipeline::MeshOptions options;
  options.size = size;
  options.order = order;
  return pipeline::generate_mesh(box, options);
}

bool has(const std::vector<core::Diagnostic>& d, const std::string& code) {
  return std::any_of(d.begin(), d.end(), [&](const core::Diagnostic& x) { return x.code == code; });
}

const NamedGroup* find(const std::vector<NamedGroup>& groups, const std::string& name) {
  for (const auto& g : groups)
    if (g.name == name) return &g;
  return nullptr;
}

TEST(ElementType, NamesParseAndKnowTheirOrder) {
  EXPECT_EQ(parse_element_type("c3d8i"), ElementType::C3D8I);
  EXPECT_EQ(parse_element_type("C3D20R"), ElementType::C3D20R);
  EXPECT_FALSE(parse_element_type("C3D27"));
  EXPECT_FALSE(parse_element_type(""));
  EXPECT_EQ(element_order(ElementType::C3D8R), 1);
  EXPECT_EQ(element_order(ElementType::C3D20), 2);
  EXPECT_TRUE(reduced_integration(ElementType::C3D20R));
  EXPECT_FALSE(reduced_integration(ElementType::C3D8I));
  ElementChoiceOptions bad;
  bad.requested = "hex8";
  EXPECT_THROW(bad.validate(), std::invalid_argument);
}

TEST(ElementType, DefaultsAvoidWhatIsKnownToFail) {
  const occ::Solid beam = occ::make_box(100, 10, 10);
  // Two elements through the thickness: C3D8I; one: reduced integration refused.
  const auto two = mesh_box(beam, 5);
  ASSERT_TRUE(two.ok);
  ElementChoice c = choose_element_type(two.mesh, two.scaled_jacobian, {});
  ASSERT_TRUE(c.ok);
  EXPECT_EQ(c.type, ElementType::C3D8I);
  EXPECT_EQ(c.one_through_thickness, 0u);

  const auto one = mesh_box(beam, 10);
  ASSERT_TRUE(one.ok);
  ElementChoiceOptions reduced;
  reduced.requested = "C3D8R";
  c = choose_element_type(one.mesh, one.scaled_jacobian, reduced);
  EXPECT_FALSE(c.ok);
  EXPECT_TRUE(has(c.diagnostics, "reduced_integration_thin"));
  EXPECT_EQ(c.one_through_thickness, one.mesh.num_hexes());
  reduced.requested = "C3D8R";
  c = choose_element_type(two.mesh, two.scaled_jacobian, reduced);
  EXPECT_TRUE(c.ok);  // two layers: allowed, with a warning (+32 % measured)
  EXPECT_TRUE(has(c.diagnostics, "reduced_integration_bending"));

  ElementChoiceOptions wrong_order;
  wrong_order.requested = "C3D20";
  c = choose_element_type(two.mesh, two.scaled_jacobian, wrong_order);
  EXPECT_FALSE(c.ok);
  EXPECT_TRUE(has(c.diagnostics, "element_order_mismatch"));

  // Second order one element thick: C3D20, not C3D20R.
  const auto quadratic = mesh_box(beam, 10, 2);
  ASSERT_TRUE(quadratic.ok);
  c = choose_element_type(quadratic.mesh, quadratic.scaled_jacobian, {});
  ASSERT_TRUE(c.ok);
  EXPECT_EQ(c.type, ElementType::C3D20);
  const auto quadratic2 = mesh_box(beam, 5, 2);
  c = choose_element_type(quadratic2.mesh, quadratic2.scaled_jacobian, {});
  ASSERT_TRUE(c.ok);
  EXPECT_EQ(c.type, ElementType::C3D20R);
}

TEST(ElementType, DistortedMeshesGetC3D8ByDefaultAndAWarningWhenAsked) {
  const occ::Solid beam = occ::make_box(100, 10, 10);
  const auto r = mesh_box(beam, 5);
  ASSERT_TRUE(r.ok);
  std::vector<double> sj(r.mesh.num_hexes(), 1.0);
  sj[3] = 0.1;  // one poor hex among good ones: C3D8I stays (measured: fine)
  ElementChoice c = choose_element_type(r.mesh, sj, {});
  ASSERT_TRUE(c.ok);
  EXPECT_EQ(c.type, ElementType::C3D8I);
  EXPECT_TRUE(c.diagnostics.empty());
  std::fill(sj.begin(), sj.end(), 0.45);  // a fallback-like mesh (mean 0.45 < 0.6)
  c = choose_element_type(r.mesh, sj, {});
  ASSERT_TRUE(c.ok);
  EXPECT_EQ(c.type, ElementType::C3D8);
  EXPECT_NEAR(c.mean_scaled_jacobian, 0.45, 1e-12);
  EXPECT_TRUE(has(c.diagnostics, "element_type_chosen"));
  ElementChoiceOptions asked;
  asked.requested = "C3D8I";
  c = choose_element_type(r.mesh, sj, asked);
  ASSERT_TRUE(c.ok);
  EXPECT_EQ(c.type, ElementType::C3D8I);
  EXPECT_TRUE(has(c.diagnostics, "incompatible_modes_distorted"));
}

TEST(NamedGroups, BoxGroupsHoldTheNodesAndFacesOfEachEntity) {
  const occ::Solid box = occ::make_box(4, 2, 2);
  const auto r = mesh_box(box, 1);
  ASSERT_TRUE(r.ok);
  const auto& groups = r.groups;
  ASSERT_EQ(groups.size(), 26u);  // 6 faces, 12 edges, 8 vertices
  EXPECT_EQ(groups.front().name, "Face1");
  EXPECT_EQ(groups.back().name, "Vertex8");
  for (const NamedGroup& g : groups) {
    SCOPED_TRACE(g.name);
    // Invariant: every node of a group lies on its entity.
    for (std::int32_t n : g.nodes) {
      const core::Vec3& p = r.mesh.point(core::NodeId(n));
      const double d = g.dim == 2   ? box.distance_to_face(core::FaceId(g.id), p)
                       : g.dim == 1 ? box.distance_to_edge(core::EdgeId(g.id), p)
                                    : box.distance_to_vertex(core::VertexId(g.id), p);
      EXPECT_LT(d, 1e-9);
    }
    if (g.dim == 2) {
      // (area / size^2) quads, (cells + 1 per direction) nodes.
      const double area = box.area(core::FaceId(g.id));
      EXPECT_EQ(g.faces.size(), static_cast<std::size_t>(std::lround(area)));
      for (const GroupFace& f : g.faces)
        for (int i : core::kHexFaces[f.face])
          EXPECT_TRUE(std::binary_search(g.nodes.begin(), g.nodes.end(),
                                         r.mesh.hex(core::HexId(f.hex))[i]));
    }
    if (g.dim == 1) {
      const double length = box.edge_length(core::EdgeId(g.id));
      EXPECT_EQ(g.edges.size(), static_cast<std::size_t>(std::lround(length)));
      EXPECT_EQ(g.nodes.size(), g.edges.size() + 1);
    }
    if (g.dim == 0) EXPECT_EQ(g.nodes.size(), 1u);
  }
  // The boundary quads are each on exactly one face.
  std::size_t faces = 0;
  for (const auto& g : groups) faces += g.faces.size();
  EXPECT_EQ(faces, r.check.boundary_quads);
}

TEST(NamedGroups, InpHasNsetElsetAndSurfacePerFace) {
  const occ::Solid box = occ::make_box(2, 1, 1);
  const auto r = mesh_box(box, 1);
  ASSERT_TRUE(r.ok);
  WriteOptions options;
  options.groups = r.groups;
  std::string error;
  const std::string path = temp_path("box.inp");
  ASSERT_TRUE(write_mesh(r.mesh, path, options, &error)) << error;
  const std::string text = read_text(path);
  EXPECT_NE(text.find("*ELEMENT, TYPE=C3D8I, ELSET=SV0\n"), std::string::npos);
  EXPECT_NE(text.find("*NSET, NSET=Face1\n"), std::string::npos);
  EXPECT_NE(text.find("*ELSET, ELSET=Face1_Elements\n"), std::string::npos);
  EXPECT_EQ(text.find("*ELSET, ELSET=Face1\n"), std::string::npos);  // see inp.cpp
  EXPECT_NE(text.find("*SURFACE, NAME=Face1, TYPE=ELEMENT\n"), std::string::npos);
  EXPECT_NE(text.find("*NSET, NSET=Edge12\n"), std::string::npos);
  EXPECT_NE(text.find("*NSET, NSET=Vertex8\n"), std::string::npos);
  // Face1 of a box is x = 0: the Abaqus face of every surface line has its nodes there
  // (faces S1..S6 = nodes 1234, 5876, 1562, 2673, 3784, 4851 of the element).
  const int kAbaqusFace[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1},
                                 {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}};
  const auto surface = text.find("*SURFACE, NAME=Face1, TYPE=ELEMENT\n");
  std::istringstream lines(text.substr(surface, text.find("*", surface + 1) - surface));
  std::string line;
  std::getline(lines, line);
  int count = 0;
  while (std::getline(lines, line) && !line.empty()) {
    const int element = std::stoi(line.substr(0, line.find(',')));
    const int face = std::stoi(line.substr(line.find('S') + 1));
    ASSERT_GE(face, 1);
    ASSERT_LE(face, 6);
    for (int k : kAbaqusFace[face - 1])
      EXPECT_NEAR(r.mesh.point(core::NodeId(r.mesh.hex(core::HexId(element - 1))[k])).x(), 0.0,
                  1e-12)
          << line;
    ++count;
  }
  EXPECT_EQ(count, 1);
}

TEST(NamedGroups, MshHasPhysicalGroupsPerEntityAndReadsBack) {
  const occ::Solid box = occ::make_box(2, 1, 1);
  for (int order : {1, 2}) {
    SCOPED_TRACE(order);
    const auto r = mesh_box(box, 1, order);
    ASSERT_TRUE(r.ok);
    WriteOptions options;
    options.groups = r.groups;
    std::string error;
    const std::string path = temp_path("box" + std::to_string(order) + ".msh");
    ASSERT_TRUE(write_mesh(r.mesh, path, options, &error)) << error;
    const std::string text = read_text(path);
    EXPECT_NE(text.find("2 1 \"Face1\"\n"), std::string::npos);
    EXPECT_NE(text.find("1 12 \"Edge12\"\n"), std::string::npos);
    EXPECT_NE(text.find("0 8 \"Vertex8\"\n"), std::string::npos);
    EXPECT_NE(text.find("$Entities\n8 12 6 1\n"), std::string::npos);
    EXPECT_NE(text.find(order == 1 ? "3 1 5 2\n" : "3 1 17 2\n"), std::string::npos);
    const ReadMeshResult back = read_mesh(path);
    ASSERT_TRUE(back.ok);
    EXPECT_EQ(back.mesh.num_hexes(), r.mesh.num_hexes());
    EXPECT_EQ(back.mesh.order(), order);
    if (order == 2) EXPECT_EQ(back.mesh.mid_edge_nodes(), r.mesh.mid_edge_nodes());
    // The groups' point, line and surface elements give every node its vertex, edge or face
    // back (the check needs them: nodes on their entity, quads across edges).
    EXPECT_TRUE(back.mesh.node_classes() == r.mesh.node_classes());
    EXPECT_TRUE(
        std::any_of(back.diagnostics.begin(), back.diagnostics.end(),
                    [](const core::Diagnostic& d) { return d.code == "boundary_elements_read"; }));
  }
}

TEST(QuadraticJacobian, StraightCubeIsConstantAndAFoldedEdgeIsNegative) {
  std::array<core::Vec3, 20> p;
  const int sign[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                          {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int i = 0; i < 8; ++i) p[i] = core::Vec3(2 * sign[i][0], 2 * sign[i][1], 2 * sign[i][2]);
  for (int e = 0; e < 12; ++e) p[8 + e] = (p[core::kHexEdges[e][0]] + p[core::kHexEdges[e][1]]) / 2;
  quality::QuadraticJacobian j = quality::quadratic_hex_jacobian(p);
  EXPECT_NEAR(j.min_det, 1.0, 1e-12);  // a cube of side 2 maps [-1, 1]^3 with det 1
  EXPECT_NEAR(j.max_det, 1.0, 1e-12);
  // A mid-edge node pushed past the opposite edge folds the element near it.
  p[8] = core::Vec3(1, 2.5, 0);
  j = quality::quadratic_hex_jacobian(p);
  EXPECT_LT(j.min_det, 0);
}

TEST(SecondOrder, CylinderMidNodesLieOnTheCadAndEveryGaussPointIsPositive) {
  const occ::Solid cylinder = occ::make_cylinder(5, 10);
  const auto r = mesh_box(cylinder, 2, 2);
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  ASSERT_EQ(r.mesh.order(), 2);
  ASSERT_EQ(r.mesh.mid_edge_nodes().size(), r.mesh.num_hexes());
  EXPECT_EQ(r.check.non_positive_gauss, 0u);
  // Every mid-edge node classified on a face or edge lies on it (the check measured them)...
  EXPECT_LT(r.check.max_boundary_distance_rel, 1e-6);
  // ...and on the curved face they are off the chord, i.e. really projected.
  std::size_t off_chord = 0, on_faces = 0;
  for (std::size_t h = 0; h < r.mesh.num_hexes(); ++h)
    for (int e = 0; e < 12; ++e) {
      const core::NodeId m(r.mesh.mid_edge_nodes()[h][e]);
      if (r.mesh.node_class(m).dim != 2) continue;
      ++on_faces;
      const auto& hex = r.mesh.hex(core::HexId(static_cast<std::int32_t>(h)));
      const core::Vec3 chord = (r.mesh.point(core::NodeId(hex[core::kHexEdges[e][0]])) +
                                r.mesh.point(core::NodeId(hex[core::kHexEdges[e][1]]))) /
                               2;
      if ((r.mesh.point(m) - chord).norm() > 1e-6) ++off_chord;
    }
  EXPECT_GT(on_faces, 0u);
  EXPECT_GT(off_chord, 0u);
  // Mid-edge nodes are shared: nodes = corners + one per mesh edge (Euler: E = V + C - 1 ...
  // here simply: no two hexes give one edge two nodes).
  std::set<std::pair<std::int32_t, std::int32_t>> edges;
  for (std::size_t h = 0; h < r.mesh.num_hexes(); ++h)
    for (const auto& e : core::kHexEdges) {
      const auto& hex = r.mesh.hex(core::HexId(static_cast<std::int32_t>(h)));
      edges.insert({std::min(hex[e[0]], hex[e[1]]), std::max(hex[e[0]], hex[e[1]])});
    }
  std::set<std::int32_t> corners;
  for (const auto& hex : r.mesh.hexes()) corners.insert(hex.begin(), hex.end());
  EXPECT_EQ(r.mesh.num_nodes(), corners.size() + edges.size());
}

TEST(SecondOrder, VtuRoundTripAndInpHas20NodeElements) {
  const occ::Solid box = occ::make_box(2, 1, 1);
  const auto r = mesh_box(box, 1, 2);
  ASSERT_TRUE(r.ok);
  std::string error;
  const std::string vtu = temp_path("q.vtu");
  ASSERT_TRUE(write_mesh(r.mesh, vtu, {}, &error)) << error;
  const ReadMeshResult back = read_mesh(vtu);
  ASSERT_TRUE(back.ok);
  EXPECT_EQ(back.mesh.order(), 2);
  EXPECT_EQ(back.mesh.mid_edge_nodes(), r.mesh.mid_edge_nodes());
  EXPECT_EQ(back.mesh.points(), r.mesh.points());
  const quality::CheckReport check = quality::check_mesh(back.mesh, &box);
  EXPECT_TRUE(check.valid);
  EXPECT_EQ(check.order, 2);
  EXPECT_EQ(check.unused_nodes, 0u);

  const std::string inp = temp_path("q.inp");
  WriteOptions options;
  options.element = ElementType::C3D20;
  ASSERT_TRUE(write_mesh(r.mesh, inp, options, &error)) << error;
  const std::string text = read_text(inp);
  EXPECT_NE(text.find("*ELEMENT, TYPE=C3D20, ELSET=SV0\n"), std::string::npos);
  // Element 1: 11 entries, a continuation, then 10 more.
  const auto at = text.find("*ELEMENT, TYPE=C3D20, ELSET=SV0\n") + 32;
  const std::string first = text.substr(at, text.find('\n', at) - at);
  EXPECT_EQ(std::count(first.begin(), first.end(), ','), 11) << first;
  options.element = ElementType::C3D8I;  // order mismatch
  EXPECT_FALSE(write_mesh(r.mesh, inp, options, &error));
}

TEST(SecondOrder, CheckFindsAFoldedQuadraticElement) {
  const occ::Solid box = occ::make_box(1, 1, 1);
  auto r = mesh_box(box, 1, 2);
  ASSERT_TRUE(r.ok);
  core::HexMesh m = r.mesh;
  const core::NodeId mid(m.mid_edge_nodes()[0][0]);
  m.set_point(mid, m.point(mid) + core::Vec3(0, 1.4, 0));  // across the element
  const quality::CheckReport check = quality::check_mesh(m, nullptr);
  EXPECT_FALSE(check.valid);
  EXPECT_EQ(check.non_positive_gauss, 1u);
  EXPECT_TRUE(has(check.diagnostics, "inverted_quadratic_elements"));
}

}  // namespace
}  // namespace vorohex::io

namespace vorohex::io {
namespace {

// A hexahedron of a tetrahedral-fallback mesh (the 100 x 10 x 10 beam with its long edges
// filleted, radius 2, meshed at size 5 with --schemes midpoint --no-decompose: element
// 6576 of 31,736): positive at its corners and centre (scaled Jacobian 0.049) but det J < 0
// at a Gauss point; CalculiX 2.20 refused the deck ("nonpositive jacobian").
const std::array<core::Vec3, 8> kFoldedInside = {{
    {52.329454305390364, 9.796276977080689, 1.1205746071383524},
    {51.814975814104784, 9.979114627411626, 1.711720115919717},
    {51.68749224595287, 9.935068075251486, 1.494518502670466},
    {51.60548811836246, 9.881712956936735, 1.3223892358467082},
    {51.74997097859694, 9.547392819416304, 0.7328869575216024},
    {51.848015132883255, 9.801113292523024, 1.1305226239304005},
    {51.67131000804618, 9.594972461392548, 1.34282944727487},
    {51.696863684700304, 9.640446689165765, 0.8559131763694334},
}};

TEST(LinearGaussJacobian, CubeIsPositiveAndAHexFoldedInsideIsNot) {
  std::array<core::Vec3, 8> cube;
  for (int i = 0; i < 8; ++i)
    cube[i] = core::Vec3(2.0 * ((i == 1 || i == 2 || i == 5 || i == 6) ? 1 : 0),
                         2.0 * ((i == 2 || i == 3 || i == 6 || i == 7) ? 1 : 0), 2.0 * (i >= 4));
  EXPECT_NEAR(quality::linear_hex_gauss_min_det(cube), 1.0, 1e-12);
  EXPECT_GT(quality::scaled_jacobian(kFoldedInside), 0.0);
  EXPECT_LT(quality::linear_hex_gauss_min_det(kFoldedInside), 0.0);

  // The element choice warns about it.
  core::HexMesh m;
  for (const auto& p : kFoldedInside) m.add_node(p);
  m.add_hex({0, 1, 2, 3, 4, 5, 6, 7});
  const ElementChoice c = choose_element_type(m, {}, {});
  EXPECT_EQ(c.non_positive_gauss, 1u);
  EXPECT_TRUE(has(c.diagnostics, "gauss_point_jacobian"));
}

}  // namespace
}  // namespace vorohex::io
