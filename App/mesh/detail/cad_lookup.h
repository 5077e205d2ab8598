// The CAD entity a point lies on, for meshers that place nodes by geometry (multisweep,
// revolve) and classify them afterwards; where a line meets a face; a face's apexes.
#pragma once

#include <vector>

#include "core/geometry.h"
#include "core/hex_mesh.h"
#include "core/mesh_domain.h"

namespace vorohex::mesh::detail {

// Within `tol`: a vertex of the solid, else an edge, else a face; else interior. `hint`
// (the answer for a neighbouring point) is tried first among edges and faces, which saves
// the search when it holds.
core::NodeClass cad_entity_at(const core::MeshDomain& solid, const core::Vec3& p, double tol,
                              core::NodeClass hint = core::NodeClass::interior());

// The point of face f on the line through p along unit d: Newton's steps along the line onto
// the tangent plane at the face's nearest point (a few), then onto the face: where the line
// meets it transversally, the meeting point.
core::Vec3 onto_face_along(const core::MeshDomain& solid, core::FaceId f, core::Vec3 p,
                           const core::Vec3& d);

// The vertices of face f's degenerated edges inside it: a cone's apex, a sphere's pole where
// no other edge of f but a seam reaches them (a drill point's tip). A pole at a corner of the
// face (an octant of a sphere: three arcs and the pole's degenerated edge) is no apex.
std::vector<core::VertexId> apex_vertices(const core::MeshDomain& solid, core::FaceId f);

}  // namespace vorohex::mesh::detail
