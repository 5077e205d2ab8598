#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <map>
#include <set>

#include "io/io_test_util.h"
#include "io/mesh_io.h"

namespace vorohex::io {
namespace {

using testing::expect_same_mesh;
using testing::grid_mesh;
using testing::has_code;
using testing::read_text;
using testing::temp_path;
using testing::write_text;

TEST(MshIo, Ascii41RoundTripKeepsPointsExactly) {
  const core::HexMesh m = grid_mesh(3);
  const std::string path = temp_path("grid.msh");
  std::string error;
  ASSERT_TRUE(write_mesh(m, path, {}, &error)) << error;
  const std::string text = read_text(path);
  EXPECT_EQ(text.rfind("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n", 0), 0u);
  EXPECT_NE(text.find("$Entities\n0 0 0 2\n"), std::string::npos);
  const ReadMeshResult r = read_mesh(path);
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics[0]));
  EXPECT_TRUE(r.diagnostics.empty());
  expect_same_mesh(m, r.mesh, false);
}

TEST(MshIo, WriterNeedsNonNegativeSubVolumes) {
  core::HexMesh m;
  for (int i = 0; i < 8; ++i) m.add_node(core::Vec3(i & 1, (i >> 1) & 1, i >> 2));
  m.add_hex({0, 1, 3, 2, 4, 5, 7, 6}, -1);
  std::string error;
  EXPECT_FALSE(write_msh(m, temp_path("neg.msh"), {}, &error));
  EXPECT_NE(error.find("-1"), std::string::npos);
}

// Sparse node tags, a physical + elementary tag pair, and elements to skip.
const char* kMsh22 = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
1
3 1 "solid"
$EndPhysicalNames
$Nodes
9
10 0 0 0
20 1 0 0
30 1 1 0
40 0 1 0
50 0 0 1
60 1 0 1
70 1 1 1
80 0 1 1
95 0.25 0.125 -3e-2
$EndNodes
$Elements
4
1 15 2 0 1 10
2 1 2 0 1 10 20
7 3 2 0 4 10 20 30 40
9 5 2 1 3 10 20 30 40 50 60 70 80
$EndElements
)";

TEST(MshIo, Ascii22WithSparseTagsKeepsHexesAndNotesTheRest) {
  const std::string path = temp_path("v22.msh");
  write_text(path, kMsh22);
  const ReadMeshResult r = read_mesh(path);
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics[0]));
  ASSERT_EQ(r.mesh.num_nodes(), 9u);
  ASSERT_EQ(r.mesh.num_hexes(), 1u);
  EXPECT_EQ(r.mesh.hex(core::HexId(0)), (core::HexNodes{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(r.mesh.sub_volume(core::HexId(0)), 2);  // elementary volume 3
  EXPECT_EQ(r.mesh.point(core::NodeId(8)), core::Vec3(0.25, 0.125, -3e-2));
  ASSERT_EQ(r.diagnostics.size(), 1u);
  EXPECT_EQ(r.diagnostics[0].severity, core::Severity::info);
  EXPECT_NE(r.diagnostics[0].message.find("3 "), std::string::npos);
}

TEST(MshIo, Ascii22ErrorsOnMissingNodeAndTruncation) {
  const std::string path = temp_path("bad22.msh");
  std::string text = kMsh22;
  text.replace(text.find("70 80\n$EndElements"), 5, "70 81");
  write_text(path, text);
  ReadMeshResult r = read_mesh(path);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has_code(r, "unreadable_mesh"));
  const std::string full = kMsh22;
  for (std::size_t cut = 1; cut + 14 < full.size(); cut += 3) {
    write_text(path, full.substr(0, cut));
    r = read_mesh(path);
    EXPECT_FALSE(r.ok) << "cut at " << cut;
  }
}

// Binary MSH 4.1 (data size 8) as Gmsh writes it.
class BinaryMsh {
 public:
  void text(const std::string& s) { data_ += s; }
  void i32(std::int32_t v) { raw(&v, 4); }
  void u64(std::uint64_t v) { raw(&v, 8); }
  void f64(double v) { raw(&v, 8); }
  const std::string& str() const { return data_; }

 private:
  void raw(const void* p, std::size_t n) { data_.append(static_cast<const char*>(p), n); }
  std::string data_;
};

std::string binary_msh(const core::HexMesh& m) {
  BinaryMsh b;
  b.text("$MeshFormat\n4.1 1 8\n");
  b.i32(1);
  b.text("\n$EndMeshFormat\n$Entities\n");
  for (std::uint64_t c : {1, 0, 1, 2}) b.u64(c);     // points, curves, surfaces, volumes
  b.i32(1), b.f64(0), b.f64(0), b.f64(0), b.u64(0);  // one point, no physical
  b.i32(4);
  for (int k = 0; k < 6; ++k) b.f64(k);
  b.u64(0), b.u64(1), b.i32(1);  // a surface bounded by the point (content is unused)
  for (int tag : {1, 2}) {
    b.i32(tag);
    for (int k = 0; k < 6; ++k) b.f64(k);
    b.u64(1), b.i32(tag), b.u64(1), b.i32(4);
  }
  b.text("\n$EndEntities\n$Nodes\n");
  const std::uint64_t nn = m.num_nodes();
  const std::uint64_t half = nn / 2;
  b.u64(2), b.u64(nn), b.u64(1000), b.u64(1000 + 3 * (nn - 1));
  // Tags 1000, 1003, ...: sparse. The second block is parametric on a volume (u v w).
  b.i32(3), b.i32(1), b.i32(0), b.u64(half);
  for (std::uint64_t i = 0; i < half; ++i) b.u64(1000 + 3 * i);
  for (std::uint64_t i = 0; i < half; ++i)
    for (int k = 0; k < 3; ++k) b.f64(m.points()[i][k]);
  b.i32(3), b.i32(2), b.i32(1), b.u64(nn - half);
  for (std::uint64_t i = half; i < nn; ++i) b.u64(1000 + 3 * i);
  for (std::uint64_t i = half; i < nn; ++i) {
    for (int k = 0; k < 3; ++k) b.f64(m.points()[i][k]);
    for (int k = 0; k < 3; ++k) b.f64(0.5);
  }
  b.text("\n$EndNodes\n$Elements\n");
  const std::uint64_t nh = m.num_hexes();
  b.u64(3), b.u64(nh + 1), b.u64(1), b.u64(nh + 1);
  b.i32(2), b.i32(4), b.i32(3), b.u64(1);  // one quadrangle: skipped
  b.u64(nh + 1);
  for (int k = 0; k < 4; ++k) b.u64(1000 + 3 * k);
  for (int s : {0, 1}) {
    std::uint64_t count = 0;
    for (std::int32_t v : m.sub_volumes()) count += v == s;
    b.i32(3), b.i32(s + 1), b.i32(5), b.u64(count);
    for (std::size_t h = 0; h < nh; ++h) {
      if (m.sub_volumes()[h] != s) continue;
      b.u64(h + 1);
      for (std::int32_t v : m.hexes()[h]) b.u64(1000 + 3 * static_cast<std::uint64_t>(v));
    }
  }
  b.text("\n$EndElements\n");
  return b.str();
}

TEST(MshIo, Binary41IsReadBitwise) {
  const core::HexMesh m = grid_mesh(2);
  const std::string path = temp_path("binary.msh");
  const std::string data = binary_msh(m);
  write_text(path, data);
  ReadMeshResult r = read_mesh(path);
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics[0]));
  // Hexes are grouped by sub-volume in the file, so compare them as sets per volume.
  ASSERT_EQ(r.mesh.num_hexes(), m.num_hexes());
  EXPECT_EQ(0, std::memcmp(r.mesh.points().data(), m.points().data(),
                           m.num_nodes() * sizeof(core::Vec3)));
  std::multiset<std::pair<std::int32_t, core::HexNodes>> expected, got;
  for (std::size_t h = 0; h < m.num_hexes(); ++h) {
    expected.insert({m.sub_volumes()[h], m.hexes()[h]});
    got.insert({r.mesh.sub_volumes()[h], r.mesh.hexes()[h]});
  }
  EXPECT_EQ(expected, got);
  EXPECT_TRUE(has_code(r, "boundary_elements_skipped"));

  for (std::size_t cut = 1; cut + 13 < data.size(); cut += 13) {
    write_text(path, data.substr(0, cut));
    r = read_mesh(path);
    EXPECT_FALSE(r.ok) << "cut at " << cut;
  }
}

TEST(MshIo, GarbageAndUnsupportedVersionsAreErrors) {
  const std::string path = temp_path("bad.msh");
  write_text(path, "$MeshFormat\n4.0 0 8\n$EndMeshFormat\n");
  EXPECT_TRUE(has_code(read_mesh(path), "unreadable_mesh"));
  write_text(path, "solid cube\nfacet normal 0 0 1\n");
  EXPECT_TRUE(has_code(read_mesh(path), "unreadable_mesh"));
  write_text(path, "\n\n  \n");
  EXPECT_TRUE(has_code(read_mesh(path), "empty_file"));
  EXPECT_TRUE(has_code(read_mesh(temp_path("none.msh")), "file_not_found"));
  // A huge announced node count must fail without allocating it.
  write_text(path, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 999999999999 1 999999999999\n");
  EXPECT_TRUE(has_code(read_mesh(path), "unreadable_mesh"));
}

// ---------------------------------------------------------------------------------------

struct InpDeck {
  std::map<std::int64_t, core::Vec3> nodes;
  std::map<std::int64_t, std::vector<std::int64_t>> elements;
  std::map<std::string, std::set<std::int64_t>> elsets;
  std::size_t max_entries = 0;
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::size_t b = 0;
  while (true) {
    const std::size_t e = line.find(',', b);
    std::string f = line.substr(b, e == std::string::npos ? std::string::npos : e - b);
    f.erase(0, f.find_first_not_of(' '));
    out.push_back(f);
    if (e == std::string::npos) return out;
    b = e + 1;
  }
}

InpDeck parse_inp(const std::string& text) {
  InpDeck d;
  std::istringstream in(text);
  std::string line, keyword, elset;
  bool generate = false;
  while (std::getline(in, line)) {
    if (line.rfind("**", 0) == 0) continue;
    if (line[0] == '*') {
      const auto f = split(line);
      keyword = f[0];
      elset.clear();
      generate = false;
      for (const auto& p : f) {
        if (p.rfind("ELSET=", 0) == 0) elset = p.substr(6);
        if (p == "GENERATE") generate = true;
      }
      continue;
    }
    const auto f = split(line);
    d.max_entries = std::max(d.max_entries, f.size());
    if (keyword == "*NODE") {
      core::Vec3 p;
      for (int k = 0; k < 3; ++k)
        std::from_chars(f[k + 1].data(), f[k + 1].data() + f[k + 1].size(), p[k]);
      d.nodes[std::stoll(f[0])] = p;
    } else if (keyword == "*ELEMENT") {
      std::vector<std::int64_t> ids;
      for (std::size_t k = 1; k < f.size(); ++k) ids.push_back(std::stoll(f[k]));
      d.elements[std::stoll(f[0])] = ids;
      d.elsets[elset].insert(std::stoll(f[0]));
    } else if (keyword == "*ELSET" && generate) {
      for (std::int64_t e = std::stoll(f[0]); e <= std::stoll(f[1]); e += std::stoll(f[2]))
        d.elsets[elset].insert(e);
    }
  }
  return d;
}

TEST(InpIo, DeckHasNodesElementsAndOneElsetPerSubVolume) {
  core::HexMesh m = grid_mesh(3);
  // Zero up to rounding, as a mesher leaves it: CalculiX refused the shortest round-trip
  // text of these (22 characters; it reads a number in 20).
  m.set_point(core::NodeId(0),
              core::Vec3(1.4145660816281972e-30, -6.280369834734204e-16, -0.30000000000000004));
  const std::string path = temp_path("grid.inp");
  std::string error;
  ASSERT_TRUE(write_mesh(m, path, {}, &error)) << error;
  const std::string text = read_text(path);
  EXPECT_EQ(text.rfind("*HEADING\n", 0), 0u);
  EXPECT_NE(text.find("TYPE=C3D8"), std::string::npos);
  const InpDeck d = parse_inp(text);
  ASSERT_EQ(d.nodes.size(), m.num_nodes());
  ASSERT_EQ(d.elements.size(), m.num_hexes());
  EXPECT_LE(d.max_entries, 16u);
  for (std::size_t i = 0; i < m.num_nodes(); ++i)  // 13 significant digits
    EXPECT_LE((d.nodes.at(static_cast<std::int64_t>(i) + 1) - m.points()[i]).norm(),
              1e-12 * (1 + m.points()[i].norm()));
  // Every field of every *NODE line fits CalculiX's 20 characters.
  const std::size_t from = text.find("*NODE"), to = text.find("*ELEMENT");
  ASSERT_LT(from, to);
  std::size_t longest = 0, start = text.find('\n', from) + 1;
  for (std::size_t i = start; i < to; ++i)
    if (text[i] == ',' || text[i] == '\n') {
      std::size_t b = start;
      while (b < i && text[b] == ' ') ++b;
      longest = std::max(longest, i - b);
      start = i + 1;
    }
  EXPECT_LE(longest, 20u);
  for (std::size_t h = 0; h < m.num_hexes(); ++h) {
    const auto& e = d.elements.at(static_cast<std::int64_t>(h) + 1);
    ASSERT_EQ(e.size(), 8u);
    for (int k = 0; k < 8; ++k) EXPECT_EQ(e[k], m.hexes()[h][k] + 1);
    const std::string set = "SV" + std::to_string(m.sub_volumes()[h]);
    EXPECT_EQ(d.elsets.at(set).count(static_cast<std::int64_t>(h) + 1), 1u);
  }
  EXPECT_EQ(d.elsets.size(), 3u);  // SV0, SV1, EALL
  EXPECT_EQ(d.elsets.at("EALL").size(), m.num_hexes());
  EXPECT_EQ(d.elsets.at("SV0").size() + d.elsets.at("SV1").size(), m.num_hexes());
}

}  // namespace
}  // namespace vorohex::io
