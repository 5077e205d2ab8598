// Reading and writing hex meshes; the format follows the file extension.
//   .vtu  VTK XML unstructured grid (binary, base64; cell data SubVolume and ScaledJacobian;
//         point data Classification dimension and entity id)   read + write
//   .msh  Gmsh MSH 4.1 (write: ASCII; read: 4.1 ASCII/binary and 2.2 ASCII)  read + write
//   .inp  Abaqus / CalculiX, C3D8 elements                                write
#pragma once

#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"

namespace vorohex::io {

struct WriteOptions {
  // Optional per-hex scaled Jacobian to store as cell data (VTU); empty = compute it.
  std::vector<double> scaled_jacobian;
};

struct ReadMeshResult {
  core::HexMesh mesh;
  bool ok = false;
  std::vector<core::Diagnostic> diagnostics;  // why reading failed; notes (e.g. skipped
                                              // non-hex cells) otherwise
};

// Returns false and sets *error on failure (unknown extension, cannot open, ...).
bool write_mesh(const core::HexMesh& mesh, const std::string& path, const WriteOptions& options,
                std::string* error);
ReadMeshResult read_mesh(const std::string& path);

// Format-specific entry points (the dispatchers above call these).
bool write_vtu(const core::HexMesh& mesh, const std::string& path, const WriteOptions& options,
               std::string* error);
bool write_msh(const core::HexMesh& mesh, const std::string& path, std::string* error);
bool write_inp(const core::HexMesh& mesh, const std::string& path, std::string* error);
ReadMeshResult read_vtu(const std::string& path);
ReadMeshResult read_msh(const std::string& path);

}  // namespace vorohex::io
