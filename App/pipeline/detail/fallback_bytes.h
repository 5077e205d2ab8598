// The fallback's result as bytes, to cross from the child process that computes it beside
// the decomposition (pipeline/generate_mesh.cpp) to the caller: what MeshResult holds except
// the validity check, the per-hexahedron scaled Jacobians and the named groups, which the
// caller recomputes from the mesh (the check is deterministic: the same report, whose
// diagnostics are among those carried). First- and second-order meshes.
#pragma once

#include <string>

#include "pipeline/generate_mesh.h"

namespace vorohex::pipeline::detail {

// `flag` travels with the result: for the fallback beside the decomposition, whether it is
// the tet split's second chance; for that second chance beside the grid's smoothing,
// whether it ran out of its time.
std::string fallback_to_bytes(const MeshResult& result, bool flag);

// False (and `result` unspecified) when the bytes are not what fallback_to_bytes wrote.
bool fallback_from_bytes(const std::string& bytes, MeshResult& result, bool& flag);

}  // namespace vorohex::pipeline::detail
