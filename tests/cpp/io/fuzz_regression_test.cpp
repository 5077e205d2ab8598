// Inputs on which fuzz_mesh_reader (bench/fuzz) found crashes, read again the way the
// target reads them. MSH 4.1: a block count near 2^64 wrapped the running total of the
// blocks around, passed the "more than announced" check and asked std::vector for 2^64
// tags (std::length_error); in ASCII files with an unknown element type it would have
// skipped 2^64 lines.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "io/io_test_util.h"
#include "io/mesh_io.h"

namespace vorohex::io {
namespace {

namespace fs = std::filesystem;

using testing::has_code;
using testing::read_text;
using testing::temp_path;
using testing::write_text;

TEST(FuzzRegression, MeshReaderInputsAreRefused) {
  const fs::path dir = fs::path(VOROHEX_SOURCE_DIR) / "bench/fuzz/regressions/fuzz_mesh_reader";
  ASSERT_TRUE(fs::is_directory(dir)) << dir;
  int inputs = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    SCOPED_TRACE(entry.path().filename().string());
    const std::string bytes = read_text(entry.path().string());
    ASSERT_FALSE(bytes.empty());
    // The lowest bit of the first byte picks the format, as in fuzz_mesh_reader.
    const std::string path = temp_path((bytes[0] & 1) ? "input.msh" : "input.vtu");
    write_text(path, bytes.substr(1));
    const ReadMeshResult r = read_mesh(path);
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(has_code(r, "unreadable_mesh"));
    std::remove(path.c_str());
    ++inputs;
  }
  EXPECT_GE(inputs, 1);
}

constexpr const char* kHeader = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
constexpr const char* kHugeCount = "18446744073709551615";  // 2^64 - 1

TEST(FuzzRegression, MshBlockCountsThatWrapAroundAreRefused) {
  // Two node blocks announced as 1 node: 1 + (2^64 - 1) wraps to 0.
  const std::string nodes = std::string(kHeader) + "$Nodes\n2 1 1 1\n3 1 0 1\n1\n0 0 0\n3 1 0 " +
                            kHugeCount + "\n$EndNodes\n";
  // Eight nodes, then element blocks announced as 1 element, the second of an unknown type.
  std::string cube = std::string(kHeader) + "$Nodes\n1 8 1 8\n3 1 0 8\n";
  for (int i = 1; i <= 8; ++i) cube += std::to_string(i) + "\n";
  for (int i = 0; i < 8; ++i)
    cube += std::to_string(i & 1) + " " + std::to_string((i >> 1) & 1) + " " +
            std::to_string(i >> 2) + "\n";
  const std::string elements = cube +
                               "$EndNodes\n$Elements\n2 1 1 1\n3 1 5 1\n1 1 2 4 3 5 6 8 7\n" +
                               "3 1 99 " + kHugeCount + "\n$EndElements\n";
  for (const std::string& text : {nodes, elements}) {
    const std::string path = temp_path("wrap.msh");
    write_text(path, text);
    const ReadMeshResult r = read_msh(path);
    EXPECT_FALSE(r.ok);
    ASSERT_FALSE(r.diagnostics.empty());
    EXPECT_NE(r.diagnostics[0].message.find("more"), std::string::npos) << r.diagnostics[0].message;
    std::remove(path.c_str());
  }
}

}  // namespace
}  // namespace vorohex::io
