// Checks shared by the options structs' validate(): each throws std::invalid_argument with
// a message naming the field ("SweepOptions.size must be finite and > 0, got -1").
#pragma once

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace vorohex::core {

inline void require_positive(const char* field, double value) {
  if (std::isfinite(value) && value > 0) return;
  std::ostringstream s;
  s << field << " must be finite and > 0, got " << value;
  throw std::invalid_argument(s.str());
}

inline void require_at_least(const char* field, long long value, long long minimum) {
  if (value >= minimum) return;
  throw std::invalid_argument(
      std::string(field) + " must be " +
      (minimum == 1 ? std::string("> 0") : ">= " + std::to_string(minimum)) + ", got " +
      std::to_string(value));
}

}  // namespace vorohex::core
