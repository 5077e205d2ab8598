#include "core/diagnostic.h"

#include <set>

namespace vorohex::core {

const char* severity_name(Severity s) {
  switch (s) {
    case Severity::info:
      return "info";
    case Severity::warning:
      return "warning";
    case Severity::error:
      return "error";
  }
  return "error";
}

bool has_error(const std::vector<Diagnostic>& diagnostics) {
  for (const auto& d : diagnostics)
    if (d.severity == Severity::error) return true;
  return false;
}

std::string error_codes(const std::vector<Diagnostic>& diagnostics) {
  std::string codes;
  std::set<std::string> named;
  for (const auto& d : diagnostics)
    if (d.severity == Severity::error && named.insert(d.code).second)
      codes += (codes.empty() ? "" : ", ") + d.code;
  return codes;
}

std::string format(const Diagnostic& d) {
  std::string s = std::string(severity_name(d.severity)) + " [" + d.code + "] " + d.message;
  if (!d.entities.empty()) {
    s += " (";
    for (std::size_t i = 0; i < d.entities.size(); ++i) {
      if (i) s += ", ";
      s += d.entities[i];
    }
    s += ")";
  }
  return s;
}

}  // namespace vorohex::core
