#include <gtest/gtest.h>

#include <cmath>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"

namespace vorohex::core {
namespace {

TEST(HexMesh, AddAndAppendKeepsConnectivityAndClasses) {
  HexMesh a;
  for (int i = 0; i < 8; ++i) a.add_node(Vec3(i & 1, (i >> 1) & 1, i >> 2), NodeClass::on(FaceId(3)));
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

TEST(Diagnostic, FormatNamesEntities) {
  const Diagnostic d = make_error("open_shell", "The shell is not closed", {"Edge3", "Edge4"});
  EXPECT_EQ(format(d), "error [open_shell] The shell is not closed (Edge3, Edge4)");
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
