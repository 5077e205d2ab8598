// A one-to-one sweep's structure (mesh/sweep.h): the source face, the target face and, per
// source edge, its four-sided linking face. Each side of a linking face other than its
// source edge may be a chain of edges meeting at side vertices (where the chain turns by
// less than kSideTurn): a neighbour glued to the solid imprints its own vertices there - on
// the target side (a seam placed elsewhere, a T-junction) and on the linking sides too (a
// neighbour cut across at another height: the plane cuts' strips ended by mitre planes at a
// pocket's corners, whose sides the blocks beside them split).
// Internal to App/mesh (the sweep's planning and meshing).
#pragma once

#include <string>
#include <vector>

#include "core/ids.h"
#include "core/mesh_domain.h"

namespace vorohex::mesh::detail {

// An edge with the direction it is read in (points from first to last when forward).
struct Directed {
  core::EdgeId edge;
  bool forward = true;
};

// Largest turn, in degrees, between consecutive edges of a chain at their common vertex (the
// direction of the chain changes less than this: a side vertex).
constexpr double kSideTurn = 30;

// One linking face. Its wire: the source edge, then the linking chain at b (read from b up to
// b_target), the target chain, the linking chain at the source edge's other end.
// A linking side may also be a stack of faces (a neighbour glued across it cut at other
// heights: the strip's side a row of blocks touches), each four-sided, the edges between two
// of them (`separators`, read like the target chain) running from a vertex of one linking
// chain to a vertex of the other, where both chains run on straight through: they lie on one
// layer of the sweep.
struct Link {
  core::FaceId face;             // the linking face at the source (the first of the stack)
  Directed source;               // as the source loop reads it
  std::vector<Directed> target;  // read from b_target to the far linking chain's top
  std::vector<Directed> col0;    // linking chain at b, read source -> target
  std::vector<Directed> col1;    // linking chain at the other end, read source -> target
  core::VertexId b, b_target;
  std::vector<core::FaceId> stack;                // the faces above `face`, in order
  std::vector<std::vector<Directed>> separators;  // below each face of `stack`
  std::vector<int> below0, below1;                // per separator: the col0 / col1 edges below it
};

struct SweepTopology {
  core::FaceId source, target;
  std::vector<std::vector<Link>> loops;  // per source wire, per edge in wire order
  double link_length = 0;                // mean length of the linking chains
};

// The sweep structure with `source` as source, or the reason why there is none.
// `imprinted`: linking sides may be chains of edges and stacks of faces (else each is one
// edge of one face, and only the target side a chain).
std::string find_sweep_topology(const core::MeshDomain& s, core::FaceId source, SweepTopology& topo,
                                bool imprinted = false);

// Among all sources, the pair with the shortest linking chains, then the largest source; the
// reason when there is none. With `imprinted` (a sub-volume glued to its neighbours, which
// imprint their edges on it), where no pair has linking sides of one edge and one face each,
// pairs whose linking sides are chains and stacks.
std::string choose_sweep_topology(const core::MeshDomain& s, SweepTopology& best,
                                  const std::vector<int>& avoid = {}, bool imprinted = false);

// The edges of a chain, in order.
std::vector<core::EdgeId> chain_edges(const std::vector<Directed>& chain);

}  // namespace vorohex::mesh::detail
