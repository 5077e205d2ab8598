// What a stage reports besides its payload (the SMESH_ComputeError pattern): expected
// failures are diagnostics with a status, not exceptions.
#pragma once

#include <string>
#include <vector>

namespace vorohex::core {

enum class Severity { info, warning, error };

const char* severity_name(Severity s);

struct Diagnostic {
  Severity severity = Severity::error;
  std::string code;                   // stable machine-readable code, e.g. "open_shell"
  std::string message;                // one sentence a user understands
  std::vector<std::string> entities;  // FreeCAD names of the entities involved ("Face7")
};

inline Diagnostic make_error(std::string code, std::string message,
                             std::vector<std::string> entities = {}) {
  return {Severity::error, std::move(code), std::move(message), std::move(entities)};
}
inline Diagnostic make_warning(std::string code, std::string message,
                               std::vector<std::string> entities = {}) {
  return {Severity::warning, std::move(code), std::move(message), std::move(entities)};
}
inline Diagnostic make_info(std::string code, std::string message,
                            std::vector<std::string> entities = {}) {
  return {Severity::info, std::move(code), std::move(message), std::move(entities)};
}

// True if any diagnostic is an error.
bool has_error(const std::vector<Diagnostic>& diagnostics);

// Appends `from` to `to`.
inline void append(std::vector<Diagnostic>& to, const std::vector<Diagnostic>& from) {
  to.insert(to.end(), from.begin(), from.end());
}

// The codes of the errors, each once, in order: "inverted_elements, volume_mismatch".
std::string error_codes(const std::vector<Diagnostic>& diagnostics);

// "error [open_shell] The shell is not closed (Edge3, Edge4)"
std::string format(const Diagnostic& d);

}  // namespace vorohex::core
