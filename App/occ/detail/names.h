// How the readers' and the glue's messages name things: "3 solids", "Edge4, Edge7 and 2
// more".
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace vorohex::occ::detail {

inline std::string plural(int n, const char* word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

inline std::string join_names(const std::vector<std::string>& names, std::size_t max_names) {
  std::string s;
  for (std::size_t i = 0; i < names.size() && i < max_names; ++i) s += (i ? ", " : "") + names[i];
  if (names.size() > max_names) s += " and " + std::to_string(names.size() - max_names) + " more";
  return s;
}

}  // namespace vorohex::occ::detail
