// Corners where a face comes to a point: its two edges at a vertex leave in the same
// direction with the face between them (an interior angle near 0: a plate's outline tangent
// to a hole cut out of it, a crescent between two tangent circles). No quad at such a
// corner has a positive angle, so no scheme that keeps the corner as a node meshes the face
// well. The quad mesher's failures name such a corner (mesh/quad_face.cpp). The schemes'
// planners do not refuse such faces: the plane cuts' first pieces have them (HexMe i06: the
// region between a fillet and the two planes it joins), and merging takes them away.
#pragma once

#include <string>
#include <vector>

#include "core/mesh_domain.h"

namespace vorohex::core {

// One such corner: the face, the vertex, and the edges into and out of it as the face's
// wire runs.
struct Cusp {
  FaceId face;
  VertexId vertex;
  OrientedEdge in, out;
};

// Every such corner of face f. `degrees`: the largest angle counted as a point.
std::vector<Cusp> face_cusps(const MeshDomain& domain, FaceId f, double degrees = 2);
// Those at vertex v only (geometry is evaluated there only: what each edge's meshing asks).
std::vector<Cusp> cusps_at(const MeshDomain& domain, FaceId f, VertexId v, double degrees = 2);

// The signed angle (radians) at the cusp between the chords from its vertex to the points at
// arc lengths l_in and l_out along its in and out edges (each at most its edge's length):
// positive while the face lies between the chords, negative where they cross (the polygon of
// the edges' nodes would cross itself there): what a quad with its corner there and its next
// nodes at those lengths gets. Where both edges curve the same way (a crescent between a
// circle and a larger one), lengthening the chord along the larger circle closes the corner.
double cusp_signed_angle(const MeshDomain& domain, const Cusp& cusp, double l_in, double l_out);

// The first such corner of face f ("Vertex3 of Face2, where Edge4 and Edge7 meet
// tangentially"), empty if none. `degrees`: the largest angle counted as a point.
std::string face_cusp(const MeshDomain& domain, FaceId f, double degrees = 2);

// The first such corner of any face of the domain, empty if none.
std::string first_cusp(const MeshDomain& domain, double degrees = 2);

}  // namespace vorohex::core
