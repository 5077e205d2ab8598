// The Verdict hex scaled Jacobian computed from the 12 edge vectors once instead of 27 frame
// vectors: the same floating-point operations up to exact sign flips, so the value is
// bitwise equal to quality::scaled_jacobian (the smoother's floor test relies on that).
#pragma once

#include <array>

#include "core/geometry.h"

namespace vorohex::smooth::detail {

double hex_scaled_jacobian(const std::array<core::Vec3, 8>& corners);

// The nine values whose minimum hex_scaled_jacobian is: the centre frame's, then each
// corner's (normalised determinants, unclamped). A collapsed hex gives nine zeros.
std::array<double, 9> hex_frame_jacobians(const std::array<core::Vec3, 8>& corners);

}  // namespace vorohex::smooth::detail
