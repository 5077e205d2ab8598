#include "core/diagnostic.h"

#include <algorithm>
#include <cctype>
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

namespace {

// Whether the message names the entity ("Edge1", not within "Edge12").
bool names(const std::string& message, const std::string& entity) {
  for (std::size_t at = message.find(entity); at != std::string::npos;
       at = message.find(entity, at + 1)) {
    const std::size_t end = at + entity.size();
    if (end >= message.size() || !std::isdigit(static_cast<unsigned char>(message[end])))
      return true;
  }
  return false;
}

}  // namespace

std::string format(const Diagnostic& d) {
  std::string s = std::string(severity_name(d.severity)) + " [" + d.code + "] " + d.message;
  // The entities after it, unless it names them all already.
  const bool named = std::all_of(d.entities.begin(), d.entities.end(),
                                 [&](const std::string& e) { return names(d.message, e); });
  if (!d.entities.empty() && !named) {
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
