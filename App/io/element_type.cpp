#include "io/element_type.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "quality/linear_gauss_jacobian.h"
#include "quality/scaled_jacobian.h"

namespace vorohex::io {
namespace {

constexpr ElementType kAll[] = {ElementType::C3D8, ElementType::C3D8I, ElementType::C3D8R,
                                ElementType::C3D20, ElementType::C3D20R};

// Hexahedra with two opposite faces on the boundary: one element through a thickness.
std::size_t count_one_through_thickness(const core::HexMesh& mesh) {
  std::vector<std::uint8_t> on_boundary(mesh.num_hexes(), 0);  // bit f: face f on boundary
  for (const core::BoundaryFace& b : core::boundary_faces(mesh))
    on_boundary[b.hex] |= static_cast<std::uint8_t>(1u << b.face);
  std::size_t n = 0;
  // kHexFaces pairs opposite faces as (0, 1), (2, 3), (4, 5).
  for (std::uint8_t bits : on_boundary)
    if ((bits & 3u) == 3u || (bits & 12u) == 12u || (bits & 48u) == 48u) ++n;
  return n;
}

std::string format_sj(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

const char* element_type_name(ElementType type) {
  switch (type) {
    case ElementType::C3D8:
      return "C3D8";
    case ElementType::C3D8I:
      return "C3D8I";
    case ElementType::C3D8R:
      return "C3D8R";
    case ElementType::C3D20:
      return "C3D20";
    case ElementType::C3D20R:
      return "C3D20R";
  }
  return "?";
}

std::optional<ElementType> parse_element_type(const std::string& name) {
  std::string upper = name;
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  for (ElementType t : kAll)
    if (upper == element_type_name(t)) return t;
  return std::nullopt;
}

int element_order(ElementType type) {
  return type == ElementType::C3D20 || type == ElementType::C3D20R ? 2 : 1;
}

bool reduced_integration(ElementType type) {
  return type == ElementType::C3D8R || type == ElementType::C3D20R;
}

void ElementChoiceOptions::validate() const {
  if (!requested.empty() && !parse_element_type(requested))
    throw std::invalid_argument("unknown element type '" + requested +
                                "' (use C3D8, C3D8I, C3D8R, C3D20 or C3D20R)");
  if (!(incompatible_modes_min_mean_sj >= -1 && incompatible_modes_min_mean_sj <= 1))
    throw std::invalid_argument("incompatible_modes_min_mean_sj must be in [-1, 1]");
}

ElementChoice choose_element_type(const core::HexMesh& mesh,
                                  const std::vector<double>& scaled_jacobian,
                                  const ElementChoiceOptions& options) {
  ElementChoice choice;
  const int order = mesh.order();
  std::optional<ElementType> asked;
  // Hexes a solver refuses: det J <= 0 at a Gauss point of the 2 x 2 x 2 rule (corners
  // only: for a second-order mesh the 27-point check of check_mesh covers the rest).
  std::vector<std::string> folded;
  for (std::size_t h = 0; h < (order == 1 ? mesh.num_hexes() : 0); ++h)
    if (!(quality::linear_hex_gauss_min_det(
              mesh.corners(core::HexId(static_cast<std::int32_t>(h)))) > 0)) {
      ++choice.non_positive_gauss;
      if (folded.size() < 10) folded.push_back(std::to_string(h + 1));
    }
  if (choice.non_positive_gauss > 0) {
    std::string list;
    for (const auto& f : folded) list += (list.empty() ? "" : ", ") + f;
    choice.diagnostics.push_back(core::make_warning(
        "gauss_point_jacobian",
        std::to_string(choice.non_positive_gauss) +
            " hexahedra have det J <= 0 at a Gauss point of the 2 x 2 x 2 rule, which the "
            "scaled Jacobian (corners and centre) does not see; CalculiX refuses them "
            "(\"nonpositive jacobian\"): elements " +
            list + (choice.non_positive_gauss > folded.size() ? ", ..." : "")));
  }
  if (!options.requested.empty()) {
    asked = parse_element_type(options.requested);
    if (!asked) {
      choice.diagnostics.push_back(core::make_error(
          "unknown_element_type", "Unknown element type '" + options.requested +
                                      "' (use C3D8, C3D8I, C3D8R, C3D20 or C3D20R)"));
      return choice;
    }
    if (element_order(*asked) != order) {
      choice.diagnostics.push_back(core::make_error(
          "element_order_mismatch",
          std::string(element_type_name(*asked)) + " is a " +
              (element_order(*asked) == 1 ? "first" : "second") +
              "-order element but the mesh is " +
              (order == 1 ? "first order (use C3D8, C3D8I or C3D8R, or mesh with order 2)"
                          : "second order (use C3D20 or C3D20R)")));
      return choice;
    }
  }
  choice.one_through_thickness = count_one_through_thickness(mesh);
  const std::vector<double> computed = scaled_jacobian.size() == mesh.num_hexes()
                                           ? std::vector<double>{}
                                           : quality::scaled_jacobians(mesh);
  const std::vector<double>& sj = computed.empty() ? scaled_jacobian : computed;
  double sum = 0;
  for (double v : sj) sum += v;
  if (!sj.empty()) choice.mean_scaled_jacobian = sum / static_cast<double>(sj.size());
  const bool distorted_mesh = choice.mean_scaled_jacobian < options.incompatible_modes_min_mean_sj;
  const std::string thin = std::to_string(choice.one_through_thickness) +
                           " hexahedra are one element through a thickness";
  const std::string distorted = "the mean scaled Jacobian is " +
                                format_sj(choice.mean_scaled_jacobian) + ", below " +
                                format_sj(options.incompatible_modes_min_mean_sj);

  if (asked) {
    choice.type = *asked;
    if (reduced_integration(*asked) && choice.one_through_thickness > 0) {
      choice.diagnostics.push_back(core::make_error(
          "reduced_integration_thin",
          std::string(element_type_name(*asked)) + " refused: " + thin +
              ", where reduced integration hourglasses (23 to 28 times the true deflection of "
              "a cantilever); use " +
              (order == 1 ? "C3D8I" : "C3D20") + " or a smaller size"));
      return choice;
    }
    if (*asked == ElementType::C3D8I && distorted_mesh)
      choice.diagnostics.push_back(core::make_warning(
          "incompatible_modes_distorted", "C3D8I on distorted hexahedra is too soft: " + distorted +
                                              " (consider C3D8 with a finer size, or order 2)"));
    if (*asked == ElementType::C3D8R)
      choice.diagnostics.push_back(core::make_warning(
          "reduced_integration_bending",
          "C3D8R hourglasses in bending even with several elements through a thickness (a "
          "cantilever deflects 32 % too much at two, 6 % at four: bench/results/fea.md); "
          "C3D8I or order 2 do not"));
    if (*asked == ElementType::C3D8)
      choice.diagnostics.push_back(core::make_info(
          "full_integration_locking",
          "C3D8 locks in bending (a cantilever two elements thick deflects about 12 % too "
          "little); C3D8I or order 2 do not"));
    choice.ok = true;
    return choice;
  }
  if (order == 2) {
    choice.type = ElementType::C3D20R;
    if (choice.one_through_thickness > 0) {
      choice.type = ElementType::C3D20;
      choice.diagnostics.push_back(core::make_info(
          "element_type_chosen",
          "C3D20 instead of C3D20R: " + thin + ", where reduced integration hourglasses"));
    }
  } else {
    choice.type = ElementType::C3D8I;
    if (distorted_mesh) {
      choice.type = ElementType::C3D8;
      choice.diagnostics.push_back(core::make_warning(
          "element_type_chosen",
          "C3D8 instead of C3D8I: " + distorted +
              ", where incompatible modes are too soft; C3D8 locks in bending instead (use a "
              "finer size or order 2)"));
    }
  }
  choice.ok = true;
  return choice;
}

}  // namespace vorohex::io
