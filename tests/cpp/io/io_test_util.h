// Small meshes and file helpers for the io tests.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "core/hex_mesh.h"
#include "io/mesh_io.h"

namespace vorohex::io::testing {

// An n x n x n structured grid of hexahedra over [0, 1.3]^3 with awkward coordinates
// (not exactly representable in decimal), nodes classified as on a cube's vertices,
// edges, faces or interior, and sub-volume = 0 for the lower half in x, 1 for the upper.
inline core::HexMesh grid_mesh(int n = 2) {
  core::HexMesh m;
  const int k = n + 1;
  auto index = [k](int i, int j, int l) { return (l * k + j) * k + i; };
  for (int l = 0; l < k; ++l)
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i) {
        const int boundary = (i == 0 || i == n) + (j == 0 || j == n) + (l == 0 || l == n);
        core::NodeClass c = core::NodeClass::interior();
        if (boundary == 3) c = core::NodeClass::on(core::VertexId(1 + index(i, j, l) % 8));
        if (boundary == 2) c = core::NodeClass::on(core::EdgeId(1 + index(i, j, l) % 12));
        if (boundary == 1) c = core::NodeClass::on(core::FaceId(1 + index(i, j, l) % 6));
        m.add_node(
            core::Vec3(1.3 * i / n + 1e-3 / 3.0 * j, 1.3 * j / n, 1.3 * l / n + 0.1 / 7.0 * i), c);
      }
  for (int l = 0; l < n; ++l)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        m.add_hex({index(i, j, l), index(i + 1, j, l), index(i + 1, j + 1, l), index(i, j + 1, l),
                   index(i, j, l + 1), index(i + 1, j, l + 1), index(i + 1, j + 1, l + 1),
                   index(i, j + 1, l + 1)},
                  2 * i < n ? 0 : 1);
  return m;
}

// A fresh path in the test temp directory.
inline std::string temp_path(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string file =
      std::string("vorohex_io_") + info->test_suite_name() + "_" + info->name() + "_" + name;
  for (char& c : file)
    if (c == '/') c = '_';  // parameterised test names contain '/'
  return ::testing::TempDir() + file;
}

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
}

inline std::string read_text(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

inline bool has_code(const ReadMeshResult& r, const std::string& code) {
  for (const auto& d : r.diagnostics)
    if (d.code == code) return true;
  return false;
}

// Nodes, classification, hexahedra and sub-volumes equal; points bitwise.
inline void expect_same_mesh(const core::HexMesh& a, const core::HexMesh& b, bool classes) {
  ASSERT_EQ(a.num_nodes(), b.num_nodes());
  ASSERT_EQ(a.num_hexes(), b.num_hexes());
  EXPECT_EQ(0,
            std::memcmp(a.points().data(), b.points().data(), a.num_nodes() * sizeof(core::Vec3)));
  EXPECT_EQ(a.hexes(), b.hexes());
  EXPECT_EQ(a.sub_volumes(), b.sub_volumes());
  if (classes) {
    EXPECT_EQ(a.node_classes(), b.node_classes());
  }
}

}  // namespace vorohex::io::testing
