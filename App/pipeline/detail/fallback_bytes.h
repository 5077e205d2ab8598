// The fallback's result as bytes, to cross from the child process that computes it beside
// the decomposition (pipeline/generate_mesh.cpp) to the caller: what MeshResult holds except
// the validity check, the per-hexahedron scaled Jacobians and the named groups, which the
// caller recomputes from the mesh (the check is deterministic: the same report, whose
// diagnostics are among those carried). First- and second-order meshes.
#pragma once

#include <string>

#include "pipeline/generate_mesh.h"

namespace vorohex::pipeline::detail {

std::string fallback_to_bytes(const MeshResult& result, bool second_chance);

// False (and `result` unspecified) when the bytes are not what fallback_to_bytes wrote.
bool fallback_from_bytes(const std::string& bytes, MeshResult& result, bool& second_chance);

}  // namespace vorohex::pipeline::detail
