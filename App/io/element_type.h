// Which Abaqus/CalculiX solid element an INP deck declares, and where a choice is known to
// give wrong answers (issue 21, measured with CalculiX 2.20: docs/fea.md).
//   C3D8   8 nodes, full integration: locks in bending (-12 % tip deflection with two
//          elements through a cantilever's thickness)
//   C3D8I  8 nodes, incompatible modes: the first-order default; too soft on the distorted
//          hexes of a tetrahedral fallback (+12 % at mean scaled Jacobian 0.42, issue 21)
//   C3D8R  8 nodes, reduced integration: hourglasses with one element through a thickness
//          (refused), too soft with two or four (+32 %, +6 %: a warning)
//   C3D20  20 nodes, full integration
//   C3D20R 20 nodes, reduced integration: the second-order default; hourglasses like C3D8R
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"

namespace vorohex::io {

enum class ElementType { C3D8, C3D8I, C3D8R, C3D20, C3D20R };

const char* element_type_name(ElementType type);
// The element named (upper or lower case), or nullopt for an unknown name.
std::optional<ElementType> parse_element_type(const std::string& name);
int element_order(ElementType type);  // 1 (8 nodes) or 2 (20 nodes)
bool reduced_integration(ElementType type);

struct ElementChoiceOptions {
  // The element asked for; empty = the default for the mesh's order (C3D8I / C3D20R),
  // replaced by a safe one where the default is known to fail.
  std::string requested;
  // Mean scaled Jacobian of the mesh below which C3D8I is not trusted. Measured with ccx
  // (bench/results/fea.md): no per-element value predicts C3D8I's error (inner nodes moved
  // at random: within 0.3 % down to a minimum of 0.19 at mean 0.83; trapezoids: -9 % at a
  // minimum of 0.93, C3D8 -19 %); the issue measured +12 % on a fallback mesh of mean 0.42.
  // 0.6 lies between the mean measured fine and the one measured wrong.
  double incompatible_modes_min_mean_sj = 0.6;
  void validate() const;  // throws std::invalid_argument naming the bad field
};

struct ElementChoice {
  bool ok = false;                            // false: refused (diagnostics say why)
  ElementType type = ElementType::C3D8I;      // the element to write when ok
  std::vector<core::Diagnostic> diagnostics;  // warnings and the reasons for a refusal
  std::size_t one_through_thickness = 0;      // hexes with two opposite boundary faces
  double mean_scaled_jacobian = 1;            // of the mesh's hexahedra
  std::size_t non_positive_gauss = 0;         // hexes with det J <= 0 at a 2x2x2 Gauss point
                                              // (a warning: solvers refuse them)
};

// scaled_jacobian: per hex (empty = computed). An unknown name, or an order that does not
// match the mesh's, is refused; reduced integration on a mesh with a hexahedron that is one
// element through a thickness (two opposite faces on the boundary) is refused when asked
// for, avoided (C3D20) by default; C3D8I on a mesh whose mean scaled Jacobian is below the
// threshold is a warning when asked for, avoided (C3D8, with a warning) by default.
ElementChoice choose_element_type(const core::HexMesh& mesh,
                                  const std::vector<double>& scaled_jacobian,
                                  const ElementChoiceOptions& options);

}  // namespace vorohex::io
