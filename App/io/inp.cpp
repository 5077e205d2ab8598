// Abaqus / CalculiX input deck with C3D8 elements.
//
// Node order: C3D8 numbers the nodes 1-4 around one face and 5-8 around the opposite
// face, node i+4 opposite node i, which is VTK's hexahedron order. FreeCAD's wiki page
// "FEM Mesh CalculiX" maps SMESH hexa8 to C3D8 as (N1, N4, N3, N2, N5, N8, N7, N6), and
// SMESH is VTK with the same swap (DESIGN.md §4), so the two swaps cancel: C3D8 = VTK.
#include <algorithm>
#include <map>

#include "io/detail/io_common.h"
#include "io/mesh_io.h"

namespace vorohex::io {
namespace {

std::string elset_name(std::int32_t sub_volume) {
  // Set names must start with a letter and hold no '-'.
  return sub_volume >= 0 ? "SV" + std::to_string(sub_volume)
                         : "SVM" + std::to_string(-static_cast<std::int64_t>(sub_volume));
}

}  // namespace

bool write_inp(const core::HexMesh& mesh, const std::string& path, std::string* error) {
  if (!detail::check_hex_indices(mesh, error)) return false;
  detail::OutputFile out;
  if (!out.open(path, error)) return false;
  std::string& t = out.text();
  t += "*HEADING\nVoroHex hexahedral mesh: ";
  detail::append_int(&t, static_cast<std::int64_t>(mesh.num_nodes()));
  t += " nodes, ";
  detail::append_int(&t, static_cast<std::int64_t>(mesh.num_hexes()));
  t += " C3D8 elements\n*NODE, NSET=NALL\n";
  const auto& points = mesh.points();
  for (std::size_t i = 0; i < points.size(); ++i) {
    detail::append_int(&t, static_cast<std::int64_t>(i + 1));
    for (int k = 0; k < 3; ++k) {
      t += ", ";
      detail::append_double(&t, points[i][k]);
    }
    t += '\n';
    out.flush_if_full();
  }
  // One *ELEMENT block per sub-volume; element ids stay the 1-based hexahedron index.
  std::map<std::int32_t, std::vector<std::size_t>> by_sub_volume;
  const auto& sub = mesh.sub_volumes();
  for (std::size_t h = 0; h < sub.size(); ++h) by_sub_volume[sub[h]].push_back(h);
  const auto& hexes = mesh.hexes();
  for (const auto& [sv, members] : by_sub_volume) {
    t += "*ELEMENT, TYPE=C3D8, ELSET=" + elset_name(sv) + "\n";
    for (std::size_t h : members) {
      // 9 entries per line, below Abaqus' limit of 16.
      detail::append_int(&t, static_cast<std::int64_t>(h + 1));
      for (std::int32_t v : hexes[h]) {
        t += ", ";
        detail::append_int(&t, static_cast<std::int64_t>(v) + 1);
      }
      t += '\n';
      out.flush_if_full();
    }
  }
  if (!hexes.empty()) {
    t += "*ELSET, ELSET=EALL, GENERATE\n1, ";
    detail::append_int(&t, static_cast<std::int64_t>(hexes.size()));
    t += ", 1\n";
  }
  return out.close(error);
}

}  // namespace vorohex::io
