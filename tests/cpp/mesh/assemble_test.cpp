// append_part: part meshes renumbered onto the whole and merged on the faces they share;
// the check names a shared face where they do not match.
#include "mesh/assemble.h"

#include <gtest/gtest.h>

#include "mesh/map_block.h"
#include "occ/detail/fixtures.h"
#include "occ/shape_io.h"
#include "quality/check_mesh.h"

namespace vorohex::mesh {
namespace {

occ::Solid touching_boxes() {
  const std::string path = ::testing::TempDir() + "assemble_touching.brep";
  EXPECT_TRUE(occ::detail::write_fixture(occ::detail::Fixture::touching_boxes, path));
  occ::ReadOptions several;
  several.several_solids = true;
  occ::ReadResult r = occ::read_solid(path, several);
  EXPECT_TRUE(r.ok());
  return std::move(*r.solid);
}

core::HexMesh mapped(const occ::Solid& s, double size) {
  MapBlockOptions o;
  o.size = size;
  MapBlockResult r = map_block(s, o);
  EXPECT_TRUE(r.ok);
  return std::move(r.mesh);
}

TEST(AppendPart, MatchingPartMeshesShareTheirCommonFaceNodes) {
  const occ::Solid whole = touching_boxes();
  core::HexMesh mesh;
  std::size_t merged = 0;
  for (int k = 0; k < 2; ++k) {
    const occ::Solid part = whole.part(k);
    merged += append_part(mesh, whole, mapped(part, 0.25), part, k + 1, 1e-9).nodes_merged;
  }
  EXPECT_EQ(merged, 25u);
  EXPECT_EQ(mesh.num_nodes(), 225u);
  // Every classified node names an entity of the whole; shared-face nodes name that face.
  std::size_t on_interface = 0;
  for (const core::NodeClass& c : mesh.node_classes()) {
    if (c.is_interior()) continue;
    const int count = c.dim == 0   ? whole.num_vertices()
                      : c.dim == 1 ? whole.num_edges()
                                   : whole.num_faces();
    EXPECT_GE(c.id, 1);
    EXPECT_LE(c.id, count);
    on_interface += c.dim == 2 && whole.face_is_interface(core::FaceId(c.id));
  }
  EXPECT_EQ(on_interface, 9u);  // the 3 x 3 inner nodes of the shared face
  const quality::CheckReport r = quality::check_mesh(mesh, &whole);
  EXPECT_TRUE(r.valid) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics[0]));
  EXPECT_EQ(r.boundary_quads, 2u * 6u * 16u - 2u * 16u);
}

TEST(AppendPart, PartMeshesThatDifferOnTheCommonFaceAreNamedByTheCheck) {
  const occ::Solid whole = touching_boxes();
  core::HexMesh mesh;
  append_part(mesh, whole, mapped(whole.part(0), 0.25), whole.part(0), 1, 1e-9);
  const AppendPartResult second =
      append_part(mesh, whole, mapped(whole.part(1), 0.2), whole.part(1), 2, 1e-9);
  EXPECT_EQ(second.nodes_merged, 4u);  // the shared face's corners only
  const quality::CheckReport r = quality::check_mesh(mesh, &whole);
  EXPECT_FALSE(r.valid);
  int interface_face = 0;
  for (int f = 1; f <= whole.num_faces(); ++f)
    if (whole.face_is_interface(core::FaceId(f))) interface_face = f;
  bool named = false;
  for (const auto& d : r.diagnostics)
    if (d.code == "non_conforming_interface") {
      named = true;
      EXPECT_EQ(d.entities, std::vector<std::string>{"Face" + std::to_string(interface_face)});
      EXPECT_NE(d.message.find("41 boundary quads"), std::string::npos) << d.message;
    }
  EXPECT_TRUE(named);
}

TEST(AppendPart, RefusesANonsenseTolerance) {
  const occ::Solid whole = touching_boxes();
  core::HexMesh mesh;
  EXPECT_THROW(append_part(mesh, whole, mapped(whole.part(0), 0.5), whole.part(0), 1, 0),
               std::invalid_argument);
}

}  // namespace
}  // namespace vorohex::mesh
