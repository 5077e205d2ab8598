// Adjacency arrays for smoothing: node -> incident (hex, corner) and node -> smoothing
// neighbours, in compressed (CSR) form so that a sweep touches only contiguous memory.
#pragma once

#include <cstdint>
#include <vector>

#include "core/hex_mesh.h"

namespace vorohex::smooth::detail {

// For each corner of a VTK hex, its three edge neighbours ordered so that the edge vectors
// (n0 - c, n1 - c, n2 - c) form a right-handed frame on the reference cube.
inline constexpr int kCornerNeighbours[8][3] = {
    {1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7}, {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3},
};

struct Csr {
  std::vector<std::int64_t> offsets{0};  // size rows + 1
  std::vector<std::int32_t> items;
  std::size_t rows() const { return offsets.size() - 1; }
  std::int64_t begin(std::size_t r) const { return offsets[r]; }
  std::int64_t end(std::size_t r) const { return offsets[r + 1]; }
  std::int64_t size(std::size_t r) const { return offsets[r + 1] - offsets[r]; }
};

struct SmoothTopology {
  // items are hex * 8 + local corner index of the node in that hex.
  Csr node_hexes;
  // Nodes whose mean is a node's Laplacian target: all edge neighbours of an interior
  // node; neighbours along boundary-quad edges of a face node; neighbours along
  // boundary-quad edges on the same model edge (or model vertices) of an edge node; none
  // for vertex nodes.
  Csr neighbours;
  std::size_t boundary_quads = 0;
};

SmoothTopology build_topology(const core::HexMesh& mesh);

}  // namespace vorohex::smooth::detail
