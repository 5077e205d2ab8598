#include <gtest/gtest.h>
#include <zlib.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <random>

#include "io/detail/base64.h"
#include "io/detail/vtu_arrays.h"
#include "io/detail/xml_scan.h"
#include "io/io_test_util.h"
#include "io/mesh_io.h"
#include "quality/scaled_jacobian.h"

namespace vorohex::io {
namespace {

using testing::expect_same_mesh;
using testing::grid_mesh;
using testing::has_code;
using testing::read_text;
using testing::temp_path;
using testing::write_text;

// ---------------------------------------------------------------------------------------
// A VTU producer independent of write_vtu, for the layouts ParaView and VTK write.
enum class Layout { inline_binary, appended_raw, appended_base64 };

struct VtuVariant {
  Layout layout;
  bool zlib;
  bool header64;
};

std::string b64(const std::vector<std::uint8_t>& bytes) {
  std::string s(detail::base64_encoded_size(bytes.size()), '\0');
  detail::base64_encode(bytes.data(), bytes.size(), s.data());
  return s;
}

class VtuBuilder {
 public:
  explicit VtuBuilder(VtuVariant v) : v_(v) {}

  // Adds one array and returns its <DataArray> element.
  template <class T>
  std::string array(const char* type, const char* name, int components,
                    const std::vector<T>& values) {
    std::vector<std::uint8_t> raw(values.size() * sizeof(T));
    if (!raw.empty()) std::memcpy(raw.data(), values.data(), raw.size());
    std::vector<std::uint8_t> header, data;
    if (!v_.zlib) {
      put(&header, raw.size());
      data = raw;
    } else {
      const std::size_t block = 100;  // small blocks: several per array
      const std::size_t nblocks = (raw.size() + block - 1) / block;
      put(&header, nblocks);
      put(&header, block);
      put(&header, raw.size() % block);
      std::vector<std::uint8_t> sizes;
      for (std::size_t b = 0; b < nblocks; ++b) {
        const std::size_t n = std::min(block, raw.size() - b * block);
        uLongf len = compressBound(n);
        std::vector<std::uint8_t> c(len);
        EXPECT_EQ(Z_OK, compress2(c.data(), &len, raw.data() + b * block, n, 6));
        put(&header, len);
        data.insert(data.end(), c.begin(), c.begin() + len);
      }
    }
    std::string tag = std::string("<DataArray type=\"") + type + "\" Name=\"" + name +
                      "\" NumberOfComponents=\"" + std::to_string(components) + "\" format=\"";
    std::vector<std::uint8_t> all = header;
    all.insert(all.end(), data.begin(), data.end());
    // VTK encodes header and data separately when compressed, together otherwise.
    const std::string text = v_.zlib ? b64(header) + b64(data) : b64(all);
    switch (v_.layout) {
      case Layout::inline_binary:
        return tag + "binary\">\n" + text + "\n</DataArray>\n";
      case Layout::appended_raw:
        tag += "appended\" offset=\"" + std::to_string(appended_.size()) + "\"/>\n";
        appended_.append(reinterpret_cast<const char*>(all.data()), all.size());
        return tag;
      case Layout::appended_base64:
        tag += "appended\" offset=\"" + std::to_string(appended_.size()) + "\"/>\n";
        appended_ += text;
        return tag;
    }
    return "";
  }

  std::string file(const core::HexMesh& m) {
    std::vector<double> xyz;
    for (const auto& p : m.points()) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
    std::vector<std::int32_t> con, off, sub(m.sub_volumes()), id;
    std::vector<std::uint8_t> types(m.num_hexes(), 12);
    std::vector<std::int8_t> dim;
    for (const auto& h : m.hexes()) {
      con.insert(con.end(), h.begin(), h.end());
      off.push_back(static_cast<std::int32_t>(con.size()));
    }
    for (const auto& c : m.node_classes()) {
      dim.push_back(c.dim);
      id.push_back(c.id);
    }
    std::string s =
        "<?xml version=\"1.0\"?>\n<!-- made by the test -->\n"
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\"";
    s += std::string(" header_type=\"") + (v_.header64 ? "UInt64" : "UInt32") + "\"";
    if (v_.zlib) s += " compressor=\"vtkZLibDataCompressor\"";
    s += ">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"" + std::to_string(m.num_nodes()) +
         "\" NumberOfCells=\"" + std::to_string(m.num_hexes()) + "\">\n<PointData>\n";
    s += array("Int8", "ClassDim", 1, dim) + array("Int32", "ClassId", 1, id);
    s += "</PointData>\n<CellData>\n" + array("Int32", "SubVolume", 1, sub) + "</CellData>\n";
    s += "<Points>\n" + array("Float64", "Points", 3, xyz) + "</Points>\n<Cells>\n";
    s += array("Int32", "connectivity", 1, con) + array("Int32", "offsets", 1, off) +
         array("UInt8", "types", 1, types) + "</Cells>\n</Piece>\n</UnstructuredGrid>\n";
    if (v_.layout != Layout::inline_binary)
      s += std::string("<AppendedData encoding=\"") +
           (v_.layout == Layout::appended_raw ? "raw" : "base64") + "\">\n_" + appended_ +
           "\n</AppendedData>\n";
    return s + "</VTKFile>\n";
  }

 private:
  void put(std::vector<std::uint8_t>* h, std::uint64_t v) const {
    for (std::size_t i = 0; i < (v_.header64 ? 8u : 4u); ++i) h->push_back((v >> (8 * i)) & 0xff);
  }
  VtuVariant v_;
  std::string appended_;
};

// ---------------------------------------------------------------------------------------

TEST(VtuIo, BinaryRoundTripIsBitwiseAndKeepsClassification) {
  const core::HexMesh m = grid_mesh(2);
  const std::string path = temp_path("grid.vtu");
  std::string error;
  ASSERT_TRUE(write_vtu(m, path, {}, &error)) << error;
  const std::string text = read_text(path);
  EXPECT_NE(text.find("header_type=\"UInt64\""), std::string::npos);
  EXPECT_NE(text.find("<DataArray type=\"Int64\" Name=\"connectivity\""), std::string::npos);
  EXPECT_EQ(text.find("format=\"ascii\""), std::string::npos);
  const ReadMeshResult r = read_mesh(path);
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics[0]));
  EXPECT_TRUE(r.diagnostics.empty());
  expect_same_mesh(m, r.mesh, true);
}

// Reads the ScaledJacobian cell array of a written file with the detail decoder.
std::vector<double> scaled_jacobian_of(const std::string& path, std::size_t cells) {
  const std::string text = read_text(path);
  detail::XmlDocument doc;
  std::string error;
  EXPECT_TRUE(detail::scan_xml(text, "AppendedData", &doc, &error)) << error;
  detail::VtuLayout layout;
  layout.file = text;
  layout.header_uint64 = true;
  for (std::size_t e = 0; e < doc.elements.size(); ++e) {
    const std::string* name = doc.elements[e].attribute("Name");
    if (name && *name == "ScaledJacobian") {
      std::vector<double> v;
      EXPECT_TRUE(detail::read_data_array(doc, e, layout, cells, 1, &v, &error)) << error;
      return v;
    }
  }
  ADD_FAILURE() << "no ScaledJacobian array";
  return {};
}

TEST(VtuIo, ScaledJacobianIsComputedOrTakenFromOptions) {
  core::HexMesh m = grid_mesh(2);
  m.set_point(core::NodeId(13), m.point(core::NodeId(13)) + core::Vec3(0.2, 0.1, 0.05));
  const std::string path = temp_path("sj.vtu");
  std::string error;
  ASSERT_TRUE(write_vtu(m, path, {}, &error)) << error;
  EXPECT_EQ(scaled_jacobian_of(path, m.num_hexes()), quality::scaled_jacobians(m));

  WriteOptions options;
  for (std::size_t i = 0; i < m.num_hexes(); ++i)
    options.scaled_jacobian.push_back(0.125 * i - 0.3);
  ASSERT_TRUE(write_vtu(m, path, options, &error)) << error;
  EXPECT_EQ(scaled_jacobian_of(path, m.num_hexes()), options.scaled_jacobian);

  options.scaled_jacobian.pop_back();
  EXPECT_FALSE(write_vtu(m, path, options, &error));
  EXPECT_NE(error.find("scaled_jacobian"), std::string::npos);
}

class VtuVariants : public ::testing::TestWithParam<VtuVariant> {};

TEST_P(VtuVariants, ReadsWhatVtkAndParaViewWrite) {
  const core::HexMesh m = grid_mesh(3);
  const std::string path = temp_path("variant.vtu");
  write_text(path, VtuBuilder(GetParam()).file(m));
  const ReadMeshResult r = read_vtu(path);
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics[0]));
  expect_same_mesh(m, r.mesh, true);
}

INSTANTIATE_TEST_SUITE_P(Layouts, VtuVariants,
                         ::testing::Values(VtuVariant{Layout::appended_raw, true,
                                                      true},  // ParaView's default
                                           VtuVariant{Layout::appended_raw, true, false},
                                           VtuVariant{Layout::appended_raw, false, true},
                                           VtuVariant{Layout::appended_base64, true, false},
                                           VtuVariant{Layout::appended_base64, false, true},
                                           VtuVariant{Layout::inline_binary, true, true},
                                           VtuVariant{Layout::inline_binary, false, false}));

// One hexahedron (Int32 connectivity, Float32 points) and one tetrahedron, in ASCII.
std::string ascii_vtu(const std::string& connectivity) {
  return R"(<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">
  <UnstructuredGrid>
    <Piece NumberOfPoints="9" NumberOfCells="2">
      <PointData>
        <DataArray type="UInt8" Name="ClassDim" format="ascii">0 1 2 3 3 3 3 3 0</DataArray>
        <DataArray type="Int64" Name="ClassId" format="ascii">4 5 6 0 0 0 0 0 9</DataArray>
      </PointData>
      <CellData>
        <DataArray type="Int32" Name="SubVolume" format="ascii">7 8</DataArray>
      </CellData>
      <Points>
        <DataArray type="Float32" NumberOfComponents="3" format="ascii">
          0 0 0  1 0 0  1 1 0  0 1 0
          0 0 1  1 0 1  1 1 1  0 1 1  0.5 0.5 2.5
        </DataArray>
      </Points>
      <Cells>
        <DataArray type="Int32" Name="connectivity" format="ascii">)" +
         connectivity + R"(</DataArray>
        <DataArray type="Int32" Name="offsets" format="ascii">4 12</DataArray>
        <DataArray type="UInt8" Name="types" format="ascii">10 12</DataArray>
      </Cells>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
)";
}

TEST(VtuIo, AsciiWithTetAndHexKeepsTheHexWithAWarning) {
  const std::string path = temp_path("mixed.vtu");
  write_text(path, ascii_vtu("4 5 6 8  0 1 2 3 4 5 6 7"));
  const ReadMeshResult r = read_mesh(path);
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics[0]));
  ASSERT_EQ(r.mesh.num_hexes(), 1u);
  ASSERT_EQ(r.mesh.num_nodes(), 9u);
  EXPECT_EQ(r.mesh.hex(core::HexId(0)), (core::HexNodes{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(r.mesh.sub_volume(core::HexId(0)), 8);
  EXPECT_EQ(r.mesh.node_class(core::NodeId(1)), core::NodeClass::on(core::EdgeId(5)));
  EXPECT_EQ(r.mesh.node_class(core::NodeId(8)), core::NodeClass::on(core::VertexId(9)));
  EXPECT_EQ(r.mesh.point(core::NodeId(8)), core::Vec3(0.5, 0.5, 2.5));
  ASSERT_EQ(r.diagnostics.size(), 1u);
  EXPECT_EQ(r.diagnostics[0].severity, core::Severity::warning);
  EXPECT_EQ(r.diagnostics[0].code, "non_hex_cells_skipped");
  EXPECT_NE(r.diagnostics[0].message.find("Skipped 1 "), std::string::npos);
}

TEST(VtuIo, OutOfRangeConnectivityIsAnError) {
  const std::string path = temp_path("range.vtu");
  write_text(path, ascii_vtu("4 5 6 8  0 1 2 3 4 5 6 9"));
  const ReadMeshResult r = read_mesh(path);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has_code(r, "unreadable_mesh"));
  EXPECT_EQ(r.mesh.num_nodes(), 0u);
  write_text(path, ascii_vtu("4 5 6 8  0 1 2 3 4 5 6 -1"));
  EXPECT_FALSE(read_mesh(path).ok);
}

TEST(VtuIo, OnlyNonHexCellsIsAnError) {
  std::string text = ascii_vtu("4 5 6 8  0 1 2 3 4 5 6 7");
  text.replace(text.find("10 12"), 5, "10 11");  // the hex becomes a voxel
  const std::string path = temp_path("nohex.vtu");
  write_text(path, text);
  const ReadMeshResult r = read_mesh(path);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has_code(r, "unreadable_mesh"));
}

TEST(VtuIo, MissingEmptyGarbageAndTruncatedFilesAreErrors) {
  EXPECT_TRUE(has_code(read_mesh(temp_path("missing.vtu")), "file_not_found"));
  const std::string path = temp_path("bad.vtu");
  write_text(path, "");
  EXPECT_TRUE(has_code(read_mesh(path), "empty_file"));
  write_text(path, "this is not a mesh \x01\x02\xff <<<>");
  ReadMeshResult r = read_mesh(path);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has_code(r, "unreadable_mesh"));

  // Every truncation of a binary file and of an appended raw zlib file fails cleanly.
  std::string error;
  ASSERT_TRUE(write_vtu(grid_mesh(2), path, {}, &error)) << error;
  const std::string binary = read_text(path);
  const std::string appended = VtuBuilder({Layout::appended_raw, true, true}).file(grid_mesh(2));
  for (const std::string* full : {&binary, &appended}) {
    // Cuts before the end of the data (the appended block ends with its data).
    const std::size_t end =
        full == &binary ? full->rfind("</VTKFile>") : full->rfind("\n</AppendedData>");
    for (std::size_t cut = 1; cut < end; cut += 17) {
      write_text(path, full->substr(0, cut));
      r = read_mesh(path);
      EXPECT_FALSE(r.ok) << "cut at " << cut;
      EXPECT_TRUE(has_code(r, "unreadable_mesh") || has_code(r, "empty_file")) << "cut at " << cut;
    }
  }
}

TEST(VtuIo, CorruptedBytesNeverCrash) {
  const std::string good = VtuBuilder({Layout::appended_raw, true, false}).file(grid_mesh(2));
  const std::string path = temp_path("fuzz.vtu");
  std::mt19937 rng(7);
  int failures = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::string bad = good;
    for (int k = 0; k < 4; ++k) bad[rng() % bad.size()] = static_cast<char>(rng());
    write_text(path, bad);
    const ReadMeshResult r = read_mesh(path);
    if (!r.ok) {
      ++failures;
      EXPECT_TRUE(core::has_error(r.diagnostics));
    } else {
      for (const auto& h : r.mesh.hexes())
        for (std::int32_t v : h) ASSERT_LT(static_cast<std::size_t>(v), r.mesh.num_nodes());
    }
  }
  EXPECT_GT(failures, 0);
}

TEST(VtuIo, ExtensionsAreCaseInsensitiveAndUnknownOnesFail) {
  const core::HexMesh m = grid_mesh(1);
  std::string error;
  const std::string upper = temp_path("grid.VTU");
  ASSERT_TRUE(write_mesh(m, upper, {}, &error)) << error;
  EXPECT_TRUE(read_mesh(upper).ok);
  EXPECT_FALSE(write_mesh(m, temp_path("grid.stl"), {}, &error));
  EXPECT_NE(error.find("stl"), std::string::npos);
  EXPECT_FALSE(write_mesh(m, temp_path("noextension"), {}, &error));
  const ReadMeshResult r = read_mesh(temp_path("grid.obj"));
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has_code(r, "unsupported_format"));
  EXPECT_TRUE(has_code(read_mesh(temp_path("grid.inp")), "unsupported_format"));
}

TEST(VtuIo, WriterRejectsDanglingNodeIndices) {
  core::HexMesh m = grid_mesh(1);
  m.add_hex({0, 1, 2, 3, 4, 5, 6, 99});
  std::string error;
  EXPECT_FALSE(write_vtu(m, temp_path("bad.vtu"), {}, &error));
  EXPECT_NE(error.find("99"), std::string::npos);
}

// Not a pass/fail test: reports the time to write one million hexahedra.
TEST(VtuIo, WritesAMillionHexesQuickly) {
  const core::HexMesh m = grid_mesh(100);
  ASSERT_EQ(m.num_hexes(), 1000000u);
  const std::string path = temp_path("million.vtu");
  std::string error;
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_TRUE(write_vtu(m, path, {}, &error)) << error;
  const auto t1 = std::chrono::steady_clock::now();
  const ReadMeshResult r = read_vtu(path);
  const auto t2 = std::chrono::steady_clock::now();
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.mesh.num_hexes(), m.num_hexes());
  std::printf("[ timing ] write_vtu 1M hexes: %.3f s, read_vtu: %.3f s, %zu MB\n",
              std::chrono::duration<double>(t1 - t0).count(),
              std::chrono::duration<double>(t2 - t1).count(), read_text(path).size() >> 20);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace vorohex::io
