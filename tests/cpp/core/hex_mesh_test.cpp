#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"

namespace vorohex::core {
namespace {

TEST(HexMesh, AddAndAppendKeepsConnectivityAndClasses) {
  HexMesh a;
  for (int i = 0; i < 8; ++i)
    a.add_node(Vec3(i & 1, (i >> 1) & 1, i >> 2), NodeClass::on(FaceId(3)));
  a.add_hex({0, 1, 3, 2, 4, 5, 7, 6}, 5);
  HexMesh b;
  b.append(a);
  const std::size_t offset = b.append(a);
  EXPECT_EQ(offset, 8u);
  ASSERT_EQ(b.num_hexes(), 2u);
  EXPECT_EQ(b.hex(HexId(1))[0], 8);
  EXPECT_EQ(b.sub_volume(HexId(1)), 5);
  EXPECT_EQ(b.node_class(NodeId(9)), NodeClass::on(FaceId(3)));
  const BoundingBox box = b.bounding_box();
  EXPECT_DOUBLE_EQ(box.diagonal(), std::sqrt(3.0));
}

// A block of 3 x 3 x 3 hexahedra: its 56 nodes on the outside are on the boundary, the 8
// inside are not; without the middle hexahedron (a cavity), all 64 are.
TEST(HexMesh, BoundaryNodesAreTheCornersOfFacesOfOneHexahedron) {
  HexMesh m;
  auto node = [](int i, int j, int k) { return std::int32_t(i + 4 * j + 16 * k); };
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) m.add_node(Vec3(i, j, k));
  HexMesh cavity = m;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        const HexNodes h = {node(i, j, k),
                            node(i + 1, j, k),
                            node(i + 1, j + 1, k),
                            node(i, j + 1, k),
                            node(i, j, k + 1),
                            node(i + 1, j, k + 1),
                            node(i + 1, j + 1, k + 1),
                            node(i, j + 1, k + 1)};
        m.add_hex(h);
        if (!(i == 1 && j == 1 && k == 1)) cavity.add_hex(h);
      }
  const std::vector<char> b = boundary_nodes(m);
  ASSERT_EQ(b.size(), 64u);
  EXPECT_EQ(std::count(b.begin(), b.end(), 1), 56);
  EXPECT_EQ(b[std::size_t(node(1, 1, 1))], 0);
  EXPECT_EQ(b[std::size_t(node(0, 2, 3))], 1);
  const std::vector<char> c = boundary_nodes(cavity);
  EXPECT_EQ(std::count(c.begin(), c.end(), 1), 64);
}

TEST(Diagnostic, FormatNamesEntities) {
  const Diagnostic d = make_error("open_shell", "The shell is not closed", {"Edge3", "Edge4"});
  EXPECT_EQ(format(d), "error [open_shell] The shell is not closed (Edge3, Edge4)");
  // A message that names them all already does not get them again (Edge1 is not within Edge12).
  EXPECT_EQ(format(make_error("open_shell", "Edge3 and Edge4 bound one face", {"Edge3", "Edge4"})),
            "error [open_shell] Edge3 and Edge4 bound one face");
  EXPECT_EQ(format(make_error("open_shell", "Edge12 bounds one face", {"Edge1"})),
            "error [open_shell] Edge12 bounds one face (Edge1)");
  EXPECT_TRUE(has_error({make_info("x", "y"), d}));
  EXPECT_FALSE(has_error({make_warning("x", "y")}));
}

TEST(StrongId, NamesMatchFreeCad) {
  EXPECT_EQ(entity_name(FaceId(7)), "Face7");
  EXPECT_EQ(entity_name(EdgeId(5)), "Edge5");
  EXPECT_EQ(entity_name(VertexId(2)), "Vertex2");
  EXPECT_FALSE(FaceId().valid());
}

}  // namespace
}  // namespace vorohex::core
