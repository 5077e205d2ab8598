// libFuzzer target for the path of `vorohex check MESH`: the mesh readers (VTU, MSH) and,
// when reading succeeds, the mesh-intrinsic checks. The first byte picks the format (its
// lowest bit: 0 .vtu, 1 .msh); the other bytes are the file. The readers take a path, so
// the bytes go through a temporary file of this process.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "io/mesh_io.h"
#include "quality/check_mesh.h"

namespace {

std::string temp_path(const char* extension) {
  static const std::string stem =
      (std::filesystem::temp_directory_path() / ("vorohex_fuzz_mesh_" + std::to_string(::getpid())))
          .string();
  return stem + extension;
}

bool write_file(const std::string& path, const std::uint8_t* data, std::size_t size) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  const bool ok = std::fwrite(data, 1, size, f) == size;
  return std::fclose(f) == 0 && ok;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string path = temp_path((data[0] & 1) ? ".msh" : ".vtu");
  if (!write_file(path, data + 1, size - 1)) return 0;
  vorohex::io::ReadMeshResult read = vorohex::io::read_mesh(path);
  std::remove(path.c_str());
  if (read.ok) {
    const vorohex::quality::CheckOptions options;
    const vorohex::quality::CheckReport report =
        vorohex::quality::check_mesh(read.mesh, nullptr, options);
    (void)report;
  }
  return 0;
}
