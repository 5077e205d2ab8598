// The nine determinants behind the scaled Jacobian, exposed for tests and diagnostics.
#pragma once

#include <array>

#include "core/geometry.h"

namespace vorohex::quality::detail {

struct JacobianTerms {
  // Corners 0..7 (VTK order), then the centre: det of the unit edge vectors / unit axes.
  std::array<double, 9> det{};
  bool collapsed = false;  // some edge vector or axis has (relatively) zero length
};

JacobianTerms scaled_jacobian_terms(const std::array<core::Vec3, 8>& corners);

}  // namespace vorohex::quality::detail
