// A sweep's source face mesh taken from a neighbour that meshed the same face (mesh/sweep.h,
// SweepOptions::source_quads): a multisweep meshes a face it shares with a sweep as a cap;
// the sweep takes those quads as its source, so that the two meshes of the face are one. And
// its target's (SweepOptions::target_quads: a ring of sweeps, the last one's target).
#pragma once

#include <array>
#include <vector>

#include "core/geometry.h"
#include "core/ids.h"
#include "core/mesh_domain.h"
#include "mesh/quad_face.h"

namespace vorohex::mesh::detail {

// The source mesh from `quads` (corner points, either orientation) on face `source`: its
// boundary nodes are `loops` (the sweep's own, loop after loop), matched by position within
// `tol`, its other corners the inner nodes; quads turned counter-clockwise about the face's
// outward normal. False (and `out` untouched) where some boundary node is not a corner of the
// quads or the quads' sides along the boundary are fewer than its nodes (the neighbour has
// nodes there the sweep has not).
bool source_from_quads(const core::MeshDomain& solid, core::FaceId source,
                       const std::vector<std::vector<core::Vec3>>& loops,
                       const std::vector<std::array<core::Vec3, 4>>& quads, double tol,
                       QuadFaceMesh& out);

// The target's quads as a neighbour meshed that face (SweepOptions::target_quads): the swept
// target nodes P[base + nb .. base + m) (its inner nodes; P[base .. base + nb) its boundary)
// moved onto the quads' inner corners, each to the nearest, one to one, within half the
// distance to its nearest other node. False (P partly moved) where they do not pair up.
bool onto_target_quads(std::vector<core::Vec3>& P, std::size_t base, std::size_t m, std::size_t nb,
                       const std::vector<std::array<core::Vec3, 4>>& quads, double size);

}  // namespace vorohex::mesh::detail
