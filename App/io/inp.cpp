// Abaqus / CalculiX input deck: nodes, elements (C3D8/C3D8I/C3D8R or C3D20/C3D20R) per
// sub-volume, and the named groups per CAD entity as *NSET, *ELSET and *SURFACE.
//
// Node order: C3D8 numbers the nodes 1-4 around one face and 5-8 around the opposite
// face, node i+4 opposite node i, which is VTK's hexahedron order. FreeCAD's wiki page
// "FEM Mesh CalculiX" maps SMESH hexa8 to C3D8 as (N1, N4, N3, N2, N5, N8, N7, N6), and
// SMESH is VTK with the same swap (DESIGN.md §4), so the two swaps cancel: C3D8 = VTK.
// C3D20 then lists the mid-edge nodes of edges 1-2 2-3 3-4 4-1, 5-6 6-7 7-8 8-5, 1-5 2-6
// 3-7 4-8: VTK_QUADRATIC_HEXAHEDRON's order, so the 20 nodes are written as stored.
#include <algorithm>
#include <map>

#include "io/detail/abaqus_faces.h"
#include "io/detail/io_common.h"
#include "io/mesh_io.h"

namespace vorohex::io {
namespace {

std::string elset_name(std::int32_t sub_volume) {
  // Set names must start with a letter and hold no '-'.
  return sub_volume >= 0 ? "SV" + std::to_string(sub_volume)
                         : "SVM" + std::to_string(-static_cast<std::int64_t>(sub_volume));
}

// Ids 16 to a line (Abaqus' limit), 1-based.
void append_id_lines(std::string* t, const std::vector<std::int32_t>& zero_based) {
  for (std::size_t i = 0; i < zero_based.size(); ++i) {
    detail::append_int(t, static_cast<std::int64_t>(zero_based[i]) + 1);
    *t += (i + 1 == zero_based.size() || i % 16 == 15) ? "\n" : ", ";
  }
}

}  // namespace

bool write_inp(const core::HexMesh& mesh, const std::string& path, const WriteOptions& options,
               std::string* error) {
  if (!detail::check_hex_indices(mesh, error)) return false;
  const int order = mesh.order();
  const ElementType element =
      options.element ? *options.element : (order == 2 ? ElementType::C3D20R : ElementType::C3D8I);
  if (element_order(element) != order) {
    detail::set_error(error, std::string(element_type_name(element)) +
                                 " does not match the mesh's order " + std::to_string(order));
    return false;
  }
  const char* type = element_type_name(element);
  detail::OutputFile out;
  if (!out.open(path, error)) return false;
  std::string& t = out.text();
  t += "*HEADING\nVoroHex hexahedral mesh: ";
  detail::append_int(&t, static_cast<std::int64_t>(mesh.num_nodes()));
  t += " nodes, ";
  detail::append_int(&t, static_cast<std::int64_t>(mesh.num_hexes()));
  t += std::string(" ") + type + " elements\n*NODE, NSET=NALL\n";
  const auto& points = mesh.points();
  for (std::size_t i = 0; i < points.size(); ++i) {
    detail::append_int(&t, static_cast<std::int64_t>(i + 1));
    for (int k = 0; k < 3; ++k) {
      t += ", ";
      detail::append_double_20(&t, points[i][k]);  // CalculiX reads 20 characters
    }
    t += '\n';
    out.flush_if_full();
  }
  // One *ELEMENT block per sub-volume; element ids stay the 1-based hexahedron index.
  std::map<std::int32_t, std::vector<std::size_t>> by_sub_volume;
  const auto& sub = mesh.sub_volumes();
  for (std::size_t h = 0; h < sub.size(); ++h) by_sub_volume[sub[h]].push_back(h);
  const auto& hexes = mesh.hexes();
  const auto& mid = mesh.mid_edge_nodes();
  for (const auto& [sv, members] : by_sub_volume) {
    t += std::string("*ELEMENT, TYPE=") + type + ", ELSET=" + elset_name(sv) + "\n";
    for (std::size_t h : members) {
      // 9 entries per line for C3D8; C3D20 continues after 11 (a line ending in a comma).
      detail::append_int(&t, static_cast<std::int64_t>(h + 1));
      int written = 1;
      auto node = [&](std::int32_t v) {
        t += (written == 11 && order == 2) ? ",\n" : ", ";
        detail::append_int(&t, static_cast<std::int64_t>(v) + 1);
        ++written;
      };
      for (std::int32_t v : hexes[h]) node(v);
      if (order == 2)
        for (std::int32_t v : mid[h]) node(v);
      t += '\n';
      out.flush_if_full();
    }
  }
  if (!hexes.empty()) {
    t += "*ELSET, ELSET=EALL, GENERATE\n1, ";
    detail::append_int(&t, static_cast<std::int64_t>(hexes.size()));
    t += ", 1\n";
  }
  // Named groups: the nodes of every entity (NSET Face7); for faces also those element faces
  // (SURFACE Face7, for *DSLOAD and contact) and the elements having one (ELSET
  // Face7_Elements: CalculiX 2.20 reads "*DSLOAD Face7, P" as the element set when one of
  // that name exists, and then silently applies nothing).
  for (const NamedGroup& g : options.groups) {
    if (!g.nodes.empty()) {
      t += "*NSET, NSET=" + g.name + "\n";
      append_id_lines(&t, g.nodes);
    }
    if (g.faces.empty()) continue;
    std::vector<std::int32_t> elements;
    for (const GroupFace& f : g.faces) elements.push_back(f.hex);
    std::sort(elements.begin(), elements.end());
    elements.erase(std::unique(elements.begin(), elements.end()), elements.end());
    t += "*ELSET, ELSET=" + g.name + "_Elements\n";
    append_id_lines(&t, elements);
    t += "*SURFACE, NAME=" + g.name + ", TYPE=ELEMENT\n";
    for (const GroupFace& f : g.faces) {
      detail::append_int(&t, static_cast<std::int64_t>(f.hex) + 1);
      t += ", S" + std::to_string(detail::abaqus_face_number(f.face)) + "\n";
    }
    out.flush_if_full();
  }
  return out.close(error);
}

}  // namespace vorohex::io
