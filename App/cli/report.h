// Human-readable and JSON reports of `vorohex mesh` and `vorohex check`.
#pragma once

#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

#include "pipeline/generate_mesh.h"
#include "quality/check_mesh.h"

namespace vorohex::cli {

// The quality and validity figures, several lines, for people.
void print_check_report(std::ostream& out, const quality::CheckReport& report);

// JSON of a check report; mesh runs add their own fields around it.
nlohmann::json check_report_json(const quality::CheckReport& report);
nlohmann::json diagnostics_json(const std::vector<core::Diagnostic>& diagnostics);

// Named groups: one line with the counts and names (people), a list (JSON: name, entity
// kind, nodes, element faces, mesh edges).
void print_groups(std::ostream& out, const std::vector<io::NamedGroup>& groups);
nlohmann::json groups_json(const std::vector<io::NamedGroup>& groups);

// The line after a usage error: where the options are listed ("vorohex mesh --help lists
// the options"), from the command's usage text ("usage: vorohex mesh IN ..."). The whole
// usage after each error pushed the error itself out of sight.
std::string usage_hint(const char* usage);

// The report of a run refused for its input (missing, empty, unreadable, not a solid...):
// the input, `verdict` false ("ok" for mesh and decompose, "valid" for check) and the
// diagnostics saying why, so that a pipeline reading the reports finds every failure, not
// only those of files that could be read.
nlohmann::json input_error_json(const std::string& input,
                                const std::vector<core::Diagnostic>& diagnostics,
                                const char* verdict = "ok");

// Writes JSON to a file; false and *error on failure.
bool write_json(const nlohmann::json& j, const std::string& path, std::string* error);

}  // namespace vorohex::cli
