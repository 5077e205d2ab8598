// The mesh of a face that two sub-volumes share, as one of them meshed it, taken by the other
// (mesh/mesh_sub_volumes.h: a multisweep meshes first, and a sweep whose source or target is
// one of its faces takes its quads there). Where both build the same cells but their inner
// nodes lie apart (a multisweep's wall, rows extruded, against a sweep's submapped lattice,
// smoothed), the sweep's nodes are put on the multisweep's, paired by the quads'
// connectivity from the face's boundary in.
#pragma once

#include <array>
#include <vector>

#include "core/geometry.h"
#include "core/hex_mesh.h"
#include "core/ids.h"
#include "occ/solid.h"

namespace vorohex::mesh::detail {

// The boundary quads of `mesh` on face f of `solid` as corner points: every corner classified
// on f, on one of its edges or at one of its vertices, and the quad's centre on f (within a
// fifth of its diagonal: the sagitta of a quad on a curved face).
std::vector<std::array<core::Vec3, 4>> quads_on_face(const core::HexMesh& mesh,
                                                     const occ::Solid& solid, core::FaceId f);

// Points P[base .. base + m): P[base .. base + nb) the face's boundary nodes, the others its
// inner nodes; `own`: its quads (indices from base). Starting from the boundary nodes (each
// matched by position within 1e-6 * size to a corner of `quads`), each own quad is paired
// with the quad of `quads` across an edge already paired, and its other corners take that
// quad's. The inner nodes are moved only where every quad and node pairs up one to one; else
// false and P untouched.
bool onto_quads_by_connectivity(std::vector<core::Vec3>& P, std::size_t base, std::size_t m,
                                std::size_t nb, const std::vector<std::array<int, 4>>& own,
                                const std::vector<std::array<core::Vec3, 4>>& quads, double size);

}  // namespace vorohex::mesh::detail
