// Reading and writing hex meshes; the format follows the file extension.
//   .vtu  VTK XML unstructured grid (binary, base64; cell data SubVolume and ScaledJacobian;
//         point data Classification dimension and entity id)   read + write
//   .msh  Gmsh MSH 4.1 (write: ASCII; read: 4.1 ASCII/binary and 2.2 ASCII)  read + write;
//         read back, the point, line and surface elements of physical groups named
//         "Vertex1", "Edge3", "Face7" classify their nodes (the lowest dimension wins)
//   .inp  Abaqus / CalculiX, C3D8/C3D8I/C3D8R or C3D20/C3D20R elements  write
// Second-order (20-node) meshes are VTK type 25, Gmsh type 17 and C3D20(R).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"
#include "io/element_type.h"
#include "io/named_groups.h"

namespace vorohex::io {

struct WriteOptions {
  // Optional per-hex scaled Jacobian to store as cell data (VTU); empty = compute it.
  std::vector<double> scaled_jacobian;
  // INP element type; nullopt = the order's default (C3D8I, C3D20R) without any checks:
  // callers choose it with choose_element_type(). Must match the mesh's order.
  std::optional<ElementType> element;
  // Named groups per CAD entity (named_groups()): INP *NSET/*ELSET/*SURFACE, MSH physical
  // groups; VTU ignores them (its point data ClassDim/ClassId carry the same).
  std::vector<NamedGroup> groups;
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
bool write_msh(const core::HexMesh& mesh, const std::string& path, const WriteOptions& options,
               std::string* error);
bool write_inp(const core::HexMesh& mesh, const std::string& path, const WriteOptions& options,
               std::string* error);
ReadMeshResult read_vtu(const std::string& path);
ReadMeshResult read_msh(const std::string& path);

}  // namespace vorohex::io
