#include "core/diagnostic.h"

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
