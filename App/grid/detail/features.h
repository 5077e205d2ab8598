// Feature capture on the grid mesher's outer surface (the pillow layer's CAD side), in
// order: each model vertex takes its nearest outer node; each model edge becomes a chain of
// mesh edges (shortest paths on the outer quads through the nodes nearest to points along
// the curve, avoiding nodes already on a feature), its nodes spread along the curve by arc
// length; then the quads between the chains are grouped into regions, each region put on
// the model face most of its nodes projected to. What could not be captured is reported.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/hex_mesh.h"
#include "core/ids.h"
#include "core/mesh_domain.h"
#include "grid/composites.h"

namespace vorohex::grid::detail {

struct FeatureCapture {
  int vertices = 0, vertices_captured = 0;  // vertices of feature edges only
  int edges = 0, edges_captured = 0;        // seams and degenerated edges are not features
  int faces = 0, faces_captured = 0;        // a face is captured when some region lies on it
  std::size_t quads_moved = 0;         // quads of a region whose nodes first projected elsewhere
  std::size_t quads_across_edges = 0;  // quads a chain cuts along their diagonal (two faces)
  std::vector<std::string> missed;     // FreeCAD names of the entities not captured
  // Edges captured with a chain that shares nodes of another edge's chain, where the two
  // leave a common vertex tangentially and run closer than a cell: there the face between
  // them has no quads.
  std::vector<std::string> joined;
  // Entities smaller than a quarter of the size (short edges, faces narrower than that, the
  // faces they enclose, the edges and vertices of such faces): absorbed into composites
  // (grid/composites.h), not captured, on purpose.
  std::vector<std::string> absorbed;
  // Vertices where two edges of one face leave tangentially (the face comes to a point).
  std::vector<core::VertexId> cusps;
};

// Vertices take their nodes nearest first, one after another, and can cross: three vertices
// on one line, closer than two cells, took their nodes out of order (HexMe i21: the quad
// through them doubled back along the edge, a hexahedron inverted). Swaps the nodes (and
// their positions) of two targets closer than `reach` while that lowers the sum of squared
// distances from each target to its node, which keeps the order of targets on a line.
// Returns the swaps made.
std::size_t uncross(const std::vector<core::Vec3>& targets, std::vector<core::Vec3>& positions,
                    std::vector<std::int32_t>& nodes, double reach);

// The outer quads a face needs around a vertex's node, given its interior angle there
// (radians): one, or where the angle is flat or reflex (over 170 degrees: a quad's corner
// there would be flat or bent inside out) enough to split it into quads of at most 130
// degrees.
int quads_for_angle(double alpha);

// The face a region of outer quads goes on: the one with the most votes (its free nodes'
// first faces), unless that face does not border every model edge whose chain bounds the
// region (`around`) and another with votes does - then the one of those with the most.
// borders(face, edge): the face is one of the edge's faces.
int region_face(const std::map<int, int>& votes, const std::set<int>& around,
                const std::function<bool(int face, int edge)>& borders);

// normals[i]: the outward direction of outer_nodes[i]'s core node (PillowMesh): where
// several nodes are as near to a feature, the one whose direction matches the feature's
// (the mean outward normal of its faces) takes it, so a chain follows the core's edge.
// Edges take their chains in the model's order, or with `tangent_edges_last` the edges
// along which the two faces are tangent (normals within 10 degrees) after the others. With
// `share_cusps`, where two edges of one face leave a vertex tangentially (a cusp), the chain
// made second shares the first's nodes while they lie within 0.3 cells of its curve.
FeatureCapture capture_features(core::HexMesh& mesh,
                                const std::vector<std::array<std::int32_t, 4>>& outer_quads,
                                const std::vector<std::int32_t>& outer_nodes,
                                const std::vector<core::Vec3>& normals,
                                const core::MeshDomain& solid, const SmallFeatures& small,
                                double size, bool tangent_edges_last = false,
                                bool share_cusps = false);

}  // namespace vorohex::grid::detail
