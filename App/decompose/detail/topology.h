// The virtual topology of a decomposition's sub-volumes and its self-check (steps 4-5 and
// the end of decompose(); docs/decomposition.md). Internal to App/decompose.
#pragma once

#include "decompose/decompose.h"
#include "occ/solid.h"

namespace vorohex::decompose::detail {

// Each face of each sub-volume: the original face it lies on, or the decomposition face it
// is (paired between its two sub-volumes, with the quads that generated it). `tol`: model
// units.
void build_topology(const occ::Solid& solid, double tol, DecompositionResult& r);

// Once the sub-volumes are final: each edge of each sub-volume, the original edge it lies
// on, else the original face, else none (inside the solid).
void build_virtual_edges(const occ::Solid& solid, double tol, DecompositionResult& r);

// The invariants (closed, disjoint sub-volumes summing to the solid's volume; decomposition
// faces four-sided between two sub-volumes, meeting their neighbours at no angle below
// `sharp_angle` degrees). A violation downgrades r.status and is named in r.diagnostics.
// `pairs`: the final check, with the pairwise booleans and the angles (the costly part).
void self_check(const occ::Solid& solid, double tol, bool pairs, double sharp_angle,
                DecompositionResult& r);

}  // namespace vorohex::decompose::detail
