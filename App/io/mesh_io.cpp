#include "io/mesh_io.h"

#include "io/detail/io_common.h"

namespace vorohex::io {

bool write_mesh(const core::HexMesh& mesh, const std::string& path, const WriteOptions& options,
                std::string* error) {
  const std::string ext = detail::lower_extension(path);
  if (ext == "vtu") return write_vtu(mesh, path, options, error);
  if (ext == "msh") return write_msh(mesh, path, options, error);
  if (ext == "inp") return write_inp(mesh, path, options, error);
  detail::set_error(error, "Unknown mesh file extension '" + ext + "' in '" + path +
                               "' (use .vtu, .msh or .inp)");
  return false;
}

ReadMeshResult read_mesh(const std::string& path) {
  const std::string ext = detail::lower_extension(path);
  if (ext == "vtu") return read_vtu(path);
  if (ext == "msh") return read_msh(path);
  ReadMeshResult result;
  result.diagnostics.push_back(core::make_error(
      "unsupported_format", ext == "inp" ? "Reading .inp files is not supported ('" + path + "')"
                                         : "Unknown mesh file extension '" + ext + "' in '" + path +
                                               "' (use .vtu or .msh)"));
  return result;
}

}  // namespace vorohex::io
