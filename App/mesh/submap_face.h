// Submapping (paper §5.1; Whiteley et al. 1996): a face (planar or curved, with holes)
// whose boundary vertices all have interior angles near 90, 180, 270 or 360 degrees (End,
// Side, Corner, Reversal vertices) is a union of mapped blocks. Each edge gets a logical
// direction (+i, +j, -i, -j) from the turns along its loop; when, on every loop, the
// intervals along +i equal those along -i (and +j / -j), the face is meshed as the cells of
// an integer lattice inside its outer loop and outside its holes (each hole placed in the
// lattice where the face's chart puts it), with inner nodes by a discrete harmonic map in
// the face's chart, mapped onto the surface: every quad of a rectilinear planar outline is a
// rectangle.
#pragma once

#include <string>
#include <vector>

#include "core/geometry.h"
#include "core/mesh_domain.h"
#include "mesh/interval_assignment.h"
#include "mesh/quad_face.h"

namespace vorohex::mesh {

enum class VertexType { end, side, corner, reversal };  // about 90, 180, 270, 360 degrees
const char* vertex_type_name(VertexType t);

struct SubmapStructure {
  bool ok = false;
  // Why not, naming the vertex and its angle ("Vertex7 of Face3 has an interior angle of
  // 130 degrees, not near 90, 180, 270 or 360"), or the loop that does not turn once.
  std::string reason;
  // Per wire (MeshDomain::face_wires order), per edge: 0 (+i), 1 (+j), 2 (-i), 3 (-j).
  std::vector<std::vector<int>> directions;
  // Per wire, per edge: the type and interior angle (degrees) of the vertex it starts at.
  std::vector<std::vector<VertexType>> types;
  std::vector<std::vector<double>> angles;
};

// Angles within `slack` degrees of a multiple of 90 take that type. Faces of one wire of
// four End vertices are mapped faces: refused unless `mapped_too`.
SubmapStructure submap_structure(const core::MeshDomain& solid, core::FaceId face,
                                 bool mapped_too = false, double slack = 25);

// `loops`: the boundary nodes per wire in wire order (first node not repeated); `counts`:
// per wire, intervals per edge. ok false (submap_failed, with the reason) when the counts do
// not balance, a hole does not fit in the lattice, or the lattice folds on the surface.
QuadFaceMesh submap_face(const core::MeshDomain& solid, core::FaceId face,
                         const std::vector<std::vector<core::Vec3>>& loops,
                         const std::vector<std::vector<int>>& counts,
                         const SubmapStructure& structure);

// Adds each loop's two balance constraints (+i = -i, +j = -j) to an interval problem;
// `curves`: per wire, the problem's curve of each edge; `why` names the face.
void add_submap_balance(IntervalProblem& problem, const SubmapStructure& structure,
                        const std::vector<std::vector<int>>& curves, const std::string& why);

// One-wire forms (sweep sources): directions of a face of one wire that is submappable but
// not mapped (else empty), its lattice mesh and its balance.
std::vector<int> submap_directions(const core::MeshDomain& solid, core::FaceId face);
QuadFaceMesh submap_face(const core::MeshDomain& solid, core::FaceId face,
                         const std::vector<core::Vec3>& loop, const std::vector<int>& counts,
                         const std::vector<int>& directions);
void add_submap_balance(IntervalProblem& problem, const std::vector<int>& directions,
                        const std::vector<int>& curves, const std::string& why);

}  // namespace vorohex::mesh
